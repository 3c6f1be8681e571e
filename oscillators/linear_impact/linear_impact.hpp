// The harmonically forced linear oscillator against a rigid stop (the linear
// impact oscillator, docs/models.md; Shaw & Holmes 1983, Nordmark 1991):
//     free flight   ẍ + 2ζẋ + x = A cos ωt,   x < σ
//     stop          x = σ, Newton impact ẋ⁺ = −r ẋ⁻
// Chattering against the stop is resolved at its accumulation point, after
// which the mass rests on the stop (x = σ, ẋ = 0) while the forcing pushes it
// into the stop, and is released where that push vanishes.
//
// Units: the equation is non-dimensional. Time t is measured in units of
// 1/ω_n (the undamped natural period is 2π), ω is the forcing frequency over
// ω_n, and x, A and σ share one length unit (A is the force amplitude per unit
// mass over ω_n²). Between events the flow is closed-form for ζ < 1, which is
// what makes this oscillator an accuracy reference.
// State: {x, ẋ}.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string_view>
#include <vector>

#include <impactlab/contact/accumulation.hpp>
#include <impactlab/contact/newton_impact.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

// The defaults give a stable period-1 impacting orbit (one impact per forcing
// period, impact velocity ẋ⁻ ≈ 3.07) that x(0) = 0, ẋ(0) = 0 settles onto.
struct LinearImpactParameters {
  double zeta = 0.05;    // damping ratio ζ (dimensionless), >= 0
  double A = 1.0;        // forcing amplitude (length)
  double omega = 2.0;    // forcing frequency ω over the natural frequency (dimensionless), > 0
  double sigma = 0.2;    // position of the stop σ (length); the mass moves in x <= σ
  double r = 0.8;        // coefficient of restitution, [0, 1]
  AccumulationTolerance accumulation{};  // what an accumulation estimate is held to
};

class LinearImpact {
 public:
  using State = std::array<double, 2>;  // {x (length), ẋ (length per unit time)}
  [[nodiscard]] std::vector<std::string_view> state_names() const { return {"x", "x_dot"}; }
  enum class Mode {
    free,   // flight, x < σ (or leaving the stop)
    stuck,  // resting on the stop after an accumulation of impacts, x = σ, ẋ = 0
  };
  static constexpr std::size_t max_witnesses = 1;
  static constexpr int wall = 1;  // the stop, on the positive side of x

  explicit LinearImpact(const LinearImpactParameters& p)
      : p_(p),
        omega_d_(std::sqrt(std::max(1.0 - p.zeta * p.zeta, 0.0))),
        P_(p.A * (1.0 - p.omega * p.omega) / response_denominator(p)),
        Q_(2.0 * p.zeta * p.omega * p.A / response_denominator(p)) {
    // the exact flow's gap σ − x is a difference of terms as large as the
    // forced response's amplitude √(P² + Q²): its round-off is theirs
    p_.accumulation.gap_roundoff =
        std::max(p_.accumulation.gap_roundoff, 4.0 * std::numeric_limits<double>::epsilon() *
                                                   (std::fabs(p.sigma) + std::hypot(P_, Q_)));
  }

  // Whether exact_flow is available: the underdamped case, except undamped
  // forcing at resonance (ω = 1, where the particular solution is secular).
  static bool has_exact_flow(const LinearImpactParameters& p) {
    return p.zeta < 1.0 && !(p.zeta == 0.0 && p.omega == 1.0);
  }

  [[nodiscard]] const LinearImpactParameters& parameters() const { return p_; }

  // ẍ of a mass at rest on the stop (x = σ, ẋ = 0): A cos ωt − σ. Positive
  // while the forcing pushes the mass into the stop; then its rate and the
  // rate of that.
  template <class Number>
  [[nodiscard]] Number stop_push(const Number& t) const {
    using std::cos;
    return p_.A * cos(p_.omega * t) - p_.sigma;
  }
  template <class Number>
  [[nodiscard]] Number stop_push_rate(const Number& t) const {
    using std::sin;
    return -p_.A * p_.omega * sin(p_.omega * t);
  }
  [[nodiscard]] double stop_push_curvature(double t) const {
    return -p_.A * p_.omega * p_.omega * std::cos(p_.omega * t);
  }

  [[nodiscard]] double max_step() const {
    const double forcing_period = 2.0 * std::numbers::pi / p_.omega;
    const double natural_period = 2.0 * std::numbers::pi;
    return std::min(forcing_period, natural_period) / 16.0;
  }

  // written over a number type (double, or the Taylor stepper's series type)
  template <class Number>
  void rhs(Mode mode, const std::array<Number, 2>& x, std::array<Number, 2>& dxdt,
           const Number& t) const {
    if (mode == Mode::stuck) {
      dxdt[0] = 0.0;
      dxdt[1] = 0.0;
      return;
    }
    using std::cos;
    dxdt[0] = x[1];
    dxdt[1] = p_.A * cos(p_.omega * t) - 2.0 * p_.zeta * x[1] - x[0];
  }

  [[nodiscard]] std::size_t witness_count(Mode) const { return 1; }

  [[nodiscard]] TriggerDirection trigger_direction(Mode, std::size_t) const {
    return TriggerDirection::falling;
  }

  // free:  the gap σ − x to the stop (length), closing when it falls to zero
  // stuck: the push A cos ωt − σ into the stop; the mass leaves when it falls to zero
  template <class Number>
  [[nodiscard]] BasicWitnessSample<Number> witness(Mode mode, std::size_t,
                                                   const std::array<Number, 2>& x,
                                                   const Number& t) const {
    if (mode == Mode::free) return {p_.sigma - x[0], -x[1]};
    return {stop_push(t), stop_push_rate(t)};
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t, CrossingKind crossing, const State& x,
                                   double t, EventLog& log) const {
    if (mode == Mode::free) return on_stop_reached(crossing, x, t, log);
    // the push only touched zero and stays inward: the mass stays on the stop
    if (crossing == CrossingKind::grazing) return {x, Mode::stuck, t, false};
    log.record({t, EventKind::contact_end, wall, p_.sigma, 0.0, 0.0});
    return {on_stop(), Mode::free, t, false};
  }

  // The closed-form flow from (t0, x0) to t in `mode`; needs has_exact_flow.
  // free: x = e^{−ζτ}(c₁ cos ω_d τ + c₂ sin ω_d τ) + P cos ωt + Q sin ωt,
  // τ = t − t0, ω_d = √(1 − ζ²), with the particular solution's
  //     P = A (1 − ω²) / D,  Q = 2ζω A / D,  D = (1 − ω²)² + (2ζω)²
  // and c₁, c₂ fitted to x0. stuck: the state does not change.
  void exact_flow(Mode mode, const State& x0, double t0, double t, State& x) const {
    if (mode == Mode::stuck) {
      x = x0;
      return;
    }
    const double w = p_.omega;
    // particular solution and its rate at t0 and t
    const double xp0 = P_ * std::cos(w * t0) + Q_ * std::sin(w * t0);
    const double vp0 = w * (Q_ * std::cos(w * t0) - P_ * std::sin(w * t0));
    const double xp = P_ * std::cos(w * t) + Q_ * std::sin(w * t);
    const double vp = w * (Q_ * std::cos(w * t) - P_ * std::sin(w * t));
    // damped homogeneous part fitted to the initial state
    const double c1 = x0[0] - xp0;
    const double c2 = (x0[1] - vp0 + p_.zeta * c1) / omega_d_;
    const double tau = t - t0;
    const double decay = std::exp(-p_.zeta * tau);
    const double c = std::cos(omega_d_ * tau);
    const double s = std::sin(omega_d_ * tau);
    x[0] = decay * (c1 * c + c2 * s) + xp;
    x[1] = decay * ((omega_d_ * c2 - p_.zeta * c1) * c - (omega_d_ * c1 + p_.zeta * c2) * s) + vp;
  }

  // --- linearisation (core/has_jacobian.hpp), on (x, ẋ) ---

  // The flow of every mode is affine in the initial state (linear ODE, or a
  // state that does not change), so the exact flow also gives its Jacobian.
  static constexpr bool affine_flow = true;

  // free: ∂(ẋ, ẍ)/∂(x, ẋ) = [[0, 1], [−1, −2ζ]]; stuck: zero
  void jacobian(Mode mode, const State&, double, TangentMatrix& j) const {
    if (mode == Mode::stuck) {
      j = {};
      return;
    }
    j = {{{0.0, 1.0}, {-1.0, -2.0 * p_.zeta}}};
  }

  // free: the gap σ − x; stuck: the push depends on t alone
  [[nodiscard]] TangentVector witness_gradient(Mode mode, std::size_t, const State&,
                                               double) const {
    if (mode == Mode::stuck) return {0.0, 0.0};
    return {-1.0, 0.0};
  }

  // the stuck mode pins the mass to the stop at rest
  [[nodiscard]] bool pinned(Mode mode) const { return mode == Mode::stuck; }

  // An impact sets x⁺ = σ, ẋ⁺ = −r ẋ⁻: ∂g/∂x = [[0, 0], [0, −r]], no explicit
  // time dependence. A grazing touch leaves the state alone. An accumulation
  // (rest on the stop) and a release (at a time set by the forcing) collapse
  // nearby states into one.
  [[nodiscard]] ResetJacobian reset_jacobian(Mode mode, std::size_t, CrossingKind crossing,
                                             const State&, double t,
                                             const Transition<State, Mode>& after) const {
    if (crossing == CrossingKind::grazing) return identity_reset();
    if (mode == Mode::stuck || after.mode == Mode::stuck || after.time > t)
      return collapsed_reset();
    return restitution_reset(p_.r);
  }

 private:
  static double response_denominator(const LinearImpactParameters& p) {
    const double detuning = 1.0 - p.omega * p.omega;
    return detuning * detuning + 4.0 * p.zeta * p.zeta * p.omega * p.omega;
  }

  [[nodiscard]] State on_stop() const { return {p_.sigma, 0.0}; }

  // An impact (or a grazing touch) on the stop; then either flight again, or,
  // when the impacts are accumulating, a jump to their limit and rest.
  Transition<State, Mode> on_stop_reached(CrossingKind crossing, const State& x, double t,
                                          EventLog& log) const {
    if (crossing == CrossingKind::grazing) {
      log.record({t, EventKind::grazing, wall, x[0], x[1], x[1]});
      return {x, Mode::free, t, false};
    }
    // Newton's law on the gap σ − x (normal Jacobian −1, unit mass, no friction)
    const NewtonImpactResult impact = newton_impact(x[1], 1.0, -1.0, 0.0, 0.0, p_.r, 0.0);
    log.record({t, EventKind::impact, wall, x[0], x[1], impact.qdot_after});
    const State after{p_.sigma, impact.qdot_after};

    // chattering: is the stop attracting, and is the accumulation estimate good?
    // on the gap σ − x: damping 2ζ, stiffness 1 (the spring)
    const auto estimate =
        accept_accumulation({std::fabs(impact.qdot_after), stop_push(t), stop_push_rate(t), p_.r,
                             stop_push_curvature(t), 2.0 * p_.zeta, 1.0},
                            p_.accumulation);
    if (!estimate) return {after, Mode::free, t, false};
    return enter_stuck(t + estimate->remaining, estimate->error_bound, log);
  }

  // At the accumulation point the mass rests on the stop if the forcing
  // pushes it there; otherwise it leaves the stop with zero velocity.
  Transition<State, Mode> enter_stuck(double t, double time_error, EventLog& log) const {
    EventRecord accumulation{t, EventKind::accumulation, wall, p_.sigma, 0.0, 0.0};
    accumulation.accumulation_error = time_error;
    log.record(accumulation);
    if (!(stop_push(t) > 0.0)) return {on_stop(), Mode::free, t, false};
    log.record({t, EventKind::contact_start, wall, p_.sigma, 0.0, 0.0});
    return {on_stop(), Mode::stuck, t, false};
  }

  LinearImpactParameters p_;
  double omega_d_;  // damped natural frequency √(1 − ζ²) (dimensionless)
  double P_, Q_;    // cos and sin amplitudes of the particular solution (length)
};

static_assert(HybridSystem<LinearImpact>);
static_assert(HasJacobian<LinearImpact>);
static_assert(HasExactFlow<LinearImpact>);

}  // namespace impactlab
