// The parametrically excited pendulum between two walls (Jin, Hu & Bishop
// 2003) under two impact models (docs/model-card.md):
//   Model N (PendulumWalls): Newton impacts with Coulomb friction, chattering
//     resolved at its accumulation point, a sustained sliding-contact phase
//     with its normal force λ_N and friction work, release where λ_N
//     vanishes, and a typed Painlevé diagnostic where the contact problem is
//     inconsistent.
//   Model P (PaperPendulumWalls): the paper's piecewise sliding impact. An
//     impact that fails the paper's instantaneous-impact test (Eq. 25,
//     sliding_impact.hpp) holds the bob on the wall, sliding with the pivot,
//     until λ_N vanishes (Eq. 20); the bob then leaves with θ̇ = −e_n θ̇0, the
//     normal restitution applied at release (Eq. 23). Impacts that pass the
//     test, and every impact when e_t = −1, are Model N's.
//
// Coordinates: θ from the downward vertical (rad), positive towards the right
// wall x = +b. The pivot moves vertically with velocity V0 sin ωt (y down).
//     free flight   m l² θ̈ + d θ̇ + m l g_e(t) sin θ = 0,  g_e = g − V0 ω cos ωt
//     walls         θ = ±θ0, θ0 = asin(b / l)
// State: {θ (rad), θ̇ (rad/s), W_f (J)}, W_f being the work done by friction
// in contact phases since t0 (it grows only in contact modes); Model P adds
// θ̇_release (rad/s), the rate the bob leaves the wall with at the end of the
// current contact phase (0 after chattering; −e_n θ̇0 in a sliding impact).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include <impactlab/contact/accumulation.hpp>
#include <impactlab/contact/newton_impact.hpp>
#include <impactlab/contact/painleve.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/fast_trig.hpp>
#include <impactlab/core/sign.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/oscillators/pendulum_walls/sliding_impact.hpp>
#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

struct PendulumWallsParameters {
  double m = 0.5;       // bob mass (kg)
  double l = 0.7;       // rod length (m)
  double b = 0.05;      // half the distance between the walls (m)
  double d = 0.01;      // damping at the pivot (N m s / rad)
  double g = 9.81;      // gravity (m/s²)
  double V0 = 1.5;      // pivot velocity amplitude (m/s)
  double omega = 7.0;   // forcing frequency (rad/s)
  double e_n = 0.3;     // normal restitution, [0, 1]
  double e_t = -0.1;    // tangential restitution of the paper's Model P, [-1, 0]
  double mu = 0.6;      // Coulomb friction coefficient, >= 0
  AccumulationTolerance accumulation{};  // what an accumulation estimate is held to
};

enum class PendulumModel { newton, paper };

enum class PendulumMode { free, contact_right, contact_left };

template <PendulumModel model>
class BasicPendulumWalls {
 public:
  static constexpr bool is_paper_model = model == PendulumModel::paper;
  static constexpr std::size_t state_size = is_paper_model ? 4 : 3;
  using State = std::array<double, state_size>;
  [[nodiscard]] std::vector<std::string_view> state_names() const {
    if constexpr (is_paper_model) return {"theta", "theta_dot", "friction_work", "release_rate"};
    return {"theta", "theta_dot", "friction_work"};
  }
  using Mode = PendulumMode;
  static constexpr std::size_t max_witnesses = 2;

  explicit BasicPendulumWalls(const PendulumWallsParameters& p)
      : p_(p),
        theta0_(std::asin(p.b / p.l)),
        sin0_(p.b / p.l),
        cos0_(std::cos(std::asin(p.b / p.l))) {}

  [[nodiscard]] const PendulumWallsParameters& parameters() const { return p_; }
  [[nodiscard]] double wall_angle() const { return theta0_; }

  // Model P's extension of an event's record: the residuals of the impact
  // conditions at an impact, from its rate before and tangential velocity
  // (sliding_impact.hpp); NaN for another event.
  [[nodiscard]] PaperImpactResiduals impact_residuals(const EventRecord& event) const
    requires is_paper_model
  {
    if (event.kind != EventKind::impact) return {};
    return {instantaneous_impact_residual(normal_speed(event), event.tangential_velocity, p_.e_n,
                                          p_.e_t, sin0_ / cos0_),
            sliding_condition_residual(p_.V0, p_.omega, p_.g, p_.e_t, event.tangential_velocity)};
  }

  // effective gravity in the pivot's frame (m/s²) and its rate (m/s³);
  // like the right-hand side, written over a number type (a series type
  // runs through them: integrate/taylor_series.hpp)
  template <class Number>
  [[nodiscard]] Number effective_gravity(const Number& t) const {
    using std::cos;
    return p_.g - p_.V0 * p_.omega * cos(p_.omega * t);
  }
  template <class Number>
  [[nodiscard]] Number effective_gravity_rate(const Number& t) const {
    using std::sin;
    return p_.V0 * p_.omega * p_.omega * sin(p_.omega * t);
  }
  [[nodiscard]] double effective_gravity_curvature(double t) const {
    return p_.V0 * p_.omega * p_.omega * p_.omega * std::cos(p_.omega * t);
  }
  // velocity of the pivot, and of a bob resting on a wall, along the wall (m/s)
  template <class Number>
  [[nodiscard]] Number pivot_velocity(const Number& t) const {
    using std::sin;
    return p_.V0 * sin(p_.omega * t);
  }

  // bob's velocity along the wall, y down (m/s)
  [[nodiscard]] double tangential_velocity(const State& x, double t) const {
    return pivot_velocity(t) - p_.l * std::sin(x[0]) * x[1];
  }

  // Painlevé denominator cos θ0 − s μ sin θ0 (dimensionless) for slip sign s.
  template <class Number>
  [[nodiscard]] Number friction_denominator(const Number& slip_sign) const {
    return cos0_ - slip_sign * p_.mu * sin0_;
  }

  // λ_N (N) in a contact phase, same formula on both walls.
  template <class Number, class SlipSign>
  [[nodiscard]] Number normal_force(const Number& t, const SlipSign& slip_sign) const {
    return -p_.m * effective_gravity(t) * sin0_ / friction_denominator(Number(slip_sign));
  }

  // The push into `event`'s wall on the bob at rest there, where the event
  // is a landing (analysis/contact_landing.hpp): a chatter's accumulation
  // point, or an impact that leaves the bob at rest on the wall (e_n = 0,
  // or Model P's take-up); the contact phase's release witness there, the
  // frictionless normal force (N), positive where the wall holds the bob.
  [[nodiscard]] std::optional<double> landing_push(const EventRecord& event) const {
    const bool at_rest = event.kind == EventKind::impact && event.qdot_after == 0.0;
    if (event.kind != EventKind::accumulation && !at_rest) return std::nullopt;
    return normal_force(event.t, 0.0);
  }

  // E = ½ m l² θ̇² + m g l (1 − cos θ) (J), the free pendulum's energy at V0 = 0
  [[nodiscard]] double energy(const State& x) const {
    return 0.5 * p_.m * p_.l * p_.l * x[1] * x[1] + p_.m * p_.g * p_.l * (1.0 - std::cos(x[0]));
  }

  [[nodiscard]] double max_step() const {
    const double forcing_period = 2.0 * std::numbers::pi / p_.omega;
    const double natural_period = 2.0 * std::numbers::pi * std::sqrt(p_.l / p_.g);
    // the damping's relaxation time m l²/d (s): an explicit stepper cannot step
    // much past it, so that an overdamped scene (m = 1e-12 kg, d = 1e12) is
    // sized by it up front (api/run_system.hpp) instead of crawling
    const double damping_period = 2.0 * std::numbers::pi * p_.m * p_.l * p_.l / p_.d;
    return std::min({forcing_period, natural_period, damping_period}) / 16.0;
  }

  // Written once over a number type: double for the Runge–Kutta steppers, a
  // Taylor series type for the Taylor stepper (the unqualified calls find its
  // own sin, cos, sign and fabs).
  template <class Number>
  void rhs(Mode mode, const std::array<Number, state_size>& x,
           std::array<Number, state_size>& dxdt, const Number& t) const {
    if (mode == Mode::free) {
      // g_e(t) and sin θ by core/fast_trig.hpp: this is the hot loop
      const Number g_e = p_.g - p_.V0 * p_.omega * cos_phase(p_.omega * t);
      dxdt[0] = x[1];
      dxdt[1] = -(p_.d * x[1] + p_.m * p_.l * g_e * sin_angle(x[0])) / (p_.m * p_.l * p_.l);
      dxdt[2] = 0.0;
      if constexpr (is_paper_model) dxdt[3] = 0.0;
      return;
    }
    using std::fabs;
    const Number slip = pivot_velocity(t);
    dxdt[0] = 0.0;
    dxdt[1] = 0.0;
    dxdt[2] = p_.mu * normal_force(t, sign(slip)) * fabs(slip);
    if constexpr (is_paper_model) dxdt[3] = 0.0;
  }

  [[nodiscard]] std::size_t witness_count(Mode) const { return 2; }

  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    if (mode == Mode::free || k == 0) return TriggerDirection::falling;
    return TriggerDirection::either;
  }

  // free:    k = 0 angular gap to the right wall θ0 − θ, k = 1 to the left
  //          wall θ + θ0 (rad): sin is increasing on [−π/2, π/2], so these
  //          have the sign and the zeros of the gaps b ∓ l sin θ (m) without
  //          a sine per evaluation, and are in the state's units (atol)
  // contact: k = 0 release: the frictionless normal force −m g_e tan θ0 (N),
  //          which has the sign and the zeros of λ_N whenever the contact is
  //          consistent (D = cos θ0 − s μ sin θ0 > 0 for the slip sign s in
  //          force; every change of s is an event where D is checked), but no
  //          jump where the slip reverses;
  //          k = 1 tangential velocity (m/s), a slip reversal
  template <class Number>
  [[nodiscard]] BasicWitnessSample<Number> witness(Mode mode, std::size_t k,
                                                   const std::array<Number, state_size>& x,
                                                   const Number& t) const {
    if (mode == Mode::free) {
      const double side = k == 0 ? 1.0 : -1.0;
      return {theta0_ - side * x[0], -side * x[1]};
    }
    if (k == 0)
      return {normal_force(t, 0.0), -p_.m * effective_gravity_rate(t) * sin0_ / cos0_};
    using std::cos;
    return {pivot_velocity(t), p_.V0 * p_.omega * cos(p_.omega * t)};
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing,
                                   const State& x, double t, EventLog& log) const {
    if (mode == Mode::free) return on_wall_reached(k == 0 ? 1 : -1, crossing, x, t, log);
    const int wall = mode == Mode::contact_right ? 1 : -1;
    if (k == 0) return release(mode, wall, x, t, log);
    return slip_reversal(mode, wall, x, t, log);
  }

  // --- linearisation (core/has_jacobian.hpp), on (θ, θ̇); W_f is bookkeeping ---
  // Model N only: Model P's release restores a rate stored at the impact
  // (θ̇_release, outside the tangent space), so its contact phases do not
  // collapse nearby states; without these members its Lyapunov exponents and
  // Floquet multipliers are reported as not available.

  // free: ∂(θ̇, θ̈)/∂(θ, θ̇) = [[0, 1], [−g_e(t) cos θ / l, −d / (m l²)]];
  // contact: zero (θ ≡ ±θ0, θ̇ = 0)
  void jacobian(Mode mode, const State& x, double t, TangentMatrix& j) const
    requires(!is_paper_model)
  {
    if (mode != Mode::free) {
      j = {};
      return;
    }
    j = {{{0.0, 1.0},
          {-effective_gravity(t) * std::cos(x[0]) / p_.l, -p_.d / (p_.m * p_.l * p_.l)}}};
  }

  // free: the angular gaps θ0 ∓ θ; contact: the witnesses depend on t alone
  [[nodiscard]] TangentVector witness_gradient(Mode mode, std::size_t k, const State&,
                                               double) const
    requires(!is_paper_model)
  {
    if (mode != Mode::free) return {0.0, 0.0};
    return {k == 0 ? -1.0 : 1.0, 0.0};
  }

  // the contact modes pin the bob to a wall at rest
  [[nodiscard]] bool pinned(Mode mode) const
    requires(!is_paper_model)
  {
    return mode != Mode::free;
  }

  // An impact sets θ⁺ = ±θ0, θ̇⁺ = −e_n θ̇⁻: ∂g/∂x = [[0, 0], [0, −e_n]], no
  // explicit time dependence. A grazing touch leaves the state alone. Entering
  // contact (an accumulation), a release (where g_e vanishes, a time set by the
  // forcing) and a slip reversal collapse nearby states into one.
  [[nodiscard]] ResetJacobian reset_jacobian(Mode mode, std::size_t, CrossingKind crossing,
                                             const State&, double t,
                                             const Transition<State, Mode>& after) const
    requires(!is_paper_model)
  {
    if (crossing == CrossingKind::grazing || after.stop) return identity_reset();
    if (mode != Mode::free || after.mode != Mode::free || after.time > t)
      return collapsed_reset();
    return restitution_reset(p_.e_n);
  }

 private:

  static Mode contact_mode(int wall) { return wall > 0 ? Mode::contact_right : Mode::contact_left; }

  // the normal approach speed of an impact, l cos θ0 |θ̇⁻| (m/s)
  [[nodiscard]] double normal_speed(const EventRecord& impact) const {
    return p_.l * cos0_ * std::fabs(impact.qdot_before);
  }

  // the state resting on a wall; release_rate: θ̇ at the end of the contact
  // (Model P only)
  [[nodiscard]] State on_wall(int wall, double friction_work, double release_rate = 0.0) const {
    if constexpr (is_paper_model)
      return {wall * theta0_, 0.0, friction_work, release_rate};
    else
      return {wall * theta0_, 0.0, friction_work};
  }

  [[nodiscard]] static double release_rate(const State& x) {
    if constexpr (is_paper_model)
      return x[3];
    else
      return 0.0;
  }

  Transition<State, Mode> stop_painleve(Mode mode, int wall, const State& x, double t,
                                        double qdot_after, EventLog& log) const {
    EventRecord painleve{t, EventKind::painleve, wall, x[0], x[1], qdot_after};
    painleve.tangential_velocity = tangential_velocity(x, t);
    log.record(painleve);
    return {x, mode, t, true};
  }

  // An impact (or a grazing touch) on `wall`; then either free flight again,
  // or, when the impacts are accumulating, a jump to their limit and contact.
  Transition<State, Mode> on_wall_reached(int wall, CrossingKind crossing, const State& x,
                                          double t, EventLog& log) const {
    const double gamma_t = tangential_velocity(x, t);
    if (crossing == CrossingKind::grazing) {
      EventRecord graze{t, EventKind::grazing, wall, x[0], x[1], x[1]};
      graze.tangential_velocity = gamma_t;
      log.record(graze);
      return {x, Mode::free, t, false};
    }
    // wall normal Jacobian W_N = -wall l cos θ0, tangential W_T = -l sin θ = -wall l sin θ0
    const double w_n = -wall * p_.l * cos0_;
    const double w_t = -wall * p_.l * sin0_;
    const NewtonImpactResult impact =
        newton_impact(x[1], p_.m * p_.l * p_.l, w_n, w_t, gamma_t, p_.e_n, p_.mu);
    if (is_painleve(impact.denominator))
      return stop_painleve(Mode::free, wall, x, t, impact.qdot_after, log);
    EventRecord record{t, EventKind::impact, wall, x[0], x[1], impact.qdot_after};
    record.normal_impulse = impact.normal_impulse;
    record.tangential_velocity = gamma_t;
    if constexpr (is_paper_model) {
      if (!is_instantaneous_impact(normal_speed(record), gamma_t, p_.e_n, p_.e_t, sin0_ / cos0_))
        if (auto held = sliding_impact(wall, x, t, record, log)) return *held;
    }
    log.record(record);

    State after = on_wall(wall, x[2]);
    after[1] = impact.qdot_after;
    // chattering: is the wall attracting, and is the accumulation estimate good?
    const double approach = -effective_gravity(t) * sin0_ * cos0_;
    const double approach_rate = -effective_gravity_rate(t) * sin0_ * cos0_;
    const double approach_curvature = -effective_gravity_curvature(t) * sin0_ * cos0_;
    // damping d/(m l²) (1/s); the gap's stiffness g_e cos θ0 / l (1/s²)
    const double damping = p_.d / (p_.m * p_.l * p_.l);
    const double gap_stiffness = effective_gravity(t) * cos0_ / p_.l;
    const auto estimate = accept_accumulation(
        {p_.l * cos0_ * std::fabs(impact.qdot_after), approach, approach_rate, p_.e_n,
         approach_curvature, damping, gap_stiffness},
        p_.accumulation);
    if (!estimate) return {after, Mode::free, t, false};
    return enter_contact(wall, x[2], t + estimate->remaining, estimate->error_bound, log);
  }

  // Model P: the bob stays on the wall, sliding with the pivot, its normal
  // velocity taken up by an impulse with e_n = 0; the contact phase ends where
  // λ_N vanishes and release() gives back θ̇ = −e_n θ̇0. No sliding impact
  // when the wall cannot hold the bob (λ_N ≤ 0 already): the impact is then
  // Newton's, instantaneous (nullopt).
  std::optional<Transition<State, Mode>> sliding_impact(int wall, const State& x, double t,
                                                        EventRecord& record,
                                                        EventLog& log) const {
    const double slip = pivot_velocity(t);
    // at zero slip the slip about to start decides the friction direction
    const double s = slip != 0.0 ? sign(slip) : sign(std::cos(p_.omega * t));
    if (is_painleve(friction_denominator(s))) return stop_painleve(Mode::free, wall, x, t, 0.0, log);
    const double lambda = normal_force(t, s);
    if (!(lambda > 0.0)) return std::nullopt;
    const NewtonImpactResult take_up = newton_impact(
        x[1], p_.m * p_.l * p_.l, -wall * p_.l * cos0_, -wall * p_.l * sin0_,
        record.tangential_velocity, 0.0, p_.mu);
    record.qdot_after = 0.0;
    record.normal_impulse = take_up.normal_impulse;
    log.record(record);
    EventRecord start{t, EventKind::contact_start, wall, wall * theta0_, 0.0, 0.0};
    start.normal_force = lambda;
    start.tangential_velocity = slip;
    start.friction_work = x[2];
    log.record(start);
    return Transition<State, Mode>{on_wall(wall, x[2], -p_.e_n * x[1]), contact_mode(wall), t,
                                   false};
  }

  Transition<State, Mode> enter_contact(int wall, double friction_work, double t,
                                        double time_error, EventLog& log) const {
    const State resting = on_wall(wall, friction_work);
    EventRecord accumulation{t, EventKind::accumulation, wall, resting[0], 0.0, 0.0};
    accumulation.accumulation_error = time_error;
    log.record(accumulation);
    const double slip = pivot_velocity(t);
    // at zero slip the slip about to start decides the friction direction
    const double s = slip != 0.0 ? sign(slip) : sign(std::cos(p_.omega * t));
    if (is_painleve(friction_denominator(s)))
      return stop_painleve(contact_mode(wall), wall, resting, t, 0.0, log);
    const double lambda = normal_force(t, s);
    if (!(lambda > 0.0)) return {resting, Mode::free, t, false};
    EventRecord start{t, EventKind::contact_start, wall, resting[0], 0.0, 0.0};
    start.normal_force = lambda;
    start.tangential_velocity = slip;
    start.friction_work = friction_work;
    log.record(start);
    return {resting, contact_mode(wall), t, false};
  }

  Transition<State, Mode> release(Mode, int wall, const State& x, double t, EventLog& log) const {
    // in contact θ is ±θ0 exactly; a stepper's round-off (extrapolation in
    // Bulirsch–Stoer) must not move the recorded or the continued state
    const double rate = release_rate(x);
    EventRecord end{t, EventKind::contact_end, wall, wall * theta0_, 0.0, rate};
    end.normal_force = 0.0;
    end.tangential_velocity = pivot_velocity(t);
    end.friction_work = x[2];
    log.record(end);
    State left = on_wall(wall, x[2]);
    left[1] = rate;
    return {left, Mode::free, t, false};
  }

  Transition<State, Mode> slip_reversal(Mode mode, int wall, const State& x, double t,
                                        EventLog& log) const {
    const double s_new = sign(std::cos(p_.omega * t)) * (p_.V0 > 0.0 ? 1.0 : 0.0);
    const State resting = on_wall(wall, x[2], release_rate(x));
    if (is_painleve(friction_denominator(s_new)))
      return stop_painleve(mode, wall, resting, t, 0.0, log);
    EventRecord reversal{t, EventKind::slip_reversal, wall, resting[0], 0.0, 0.0};
    reversal.normal_force = normal_force(t, s_new);
    reversal.tangential_velocity = 0.0;
    reversal.friction_work = x[2];
    log.record(reversal);
    return {resting, mode, t, false};
  }

  PendulumWallsParameters p_;
  double theta0_;  // wall angle (rad)
  double sin0_;    // sin θ0 = b / l
  double cos0_;    // cos θ0
};

using PendulumWalls = BasicPendulumWalls<PendulumModel::newton>;
using PaperPendulumWalls = BasicPendulumWalls<PendulumModel::paper>;

static_assert(HybridSystem<PendulumWalls>);
static_assert(HybridSystem<PaperPendulumWalls>);
static_assert(HasJacobian<PendulumWalls>);
static_assert(!HasJacobian<PaperPendulumWalls>);

}  // namespace impactlab
