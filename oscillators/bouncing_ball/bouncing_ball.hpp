// A ball bouncing on a vertically vibrating table (docs/models.md; Holmes 1982,
// Luck & Mehta 1993):
//     table        z(t) = A sin ωt
//     free flight  ÿ = −g,  y > z
//     impact       y = z, (ẏ − ż)⁺ = −r (ẏ − ż)⁻ (Newton's law on the relative velocity)
// For small r the impacts chatter and accumulate while the table pushes the
// ball up (g + z̈ > 0): the run jumps to the accumulation point and the ball
// rides on the table (y = z, ẏ = ż) until the table decelerates faster than
// gravity (g + z̈ falls through zero), where it is released.
//
// Units: SI. y and z are heights (m), positive up; t (s); ω (rad/s).
// The table is the only wall; its events carry wall = −1 (it lies below the
// ball, on the negative side of the gap).
// State: {y, ẏ}.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string_view>
#include <vector>

#include <impactlab/contact/accumulation.hpp>
#include <impactlab/contact/newton_impact.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/fast_trig.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

// The defaults (Γ = Aω²/g ≈ 1.03, r = 0.8) have a stable period-1 orbit: one
// bounce per table period, take-off speed gπ/ω ≈ 1.03 m/s.
struct BouncingBallParameters {
  double g = 9.81;       // gravity (m/s²), > 0
  double A = 0.0112;     // table amplitude (m), >= 0
  double omega = 30.0;   // table angular frequency (rad/s), > 0
  double r = 0.8;        // coefficient of restitution, [0, 1]
  AccumulationTolerance accumulation{};  // what an accumulation estimate is held to
};

class BouncingBall {
 public:
  using State = std::array<double, 2>;  // {y (m), ẏ (m/s)}
  [[nodiscard]] std::vector<std::string_view> state_names() const { return {"y", "y_dot"}; }
  enum class Mode {
    free,   // flight, y > z (or leaving the table)
    stuck,  // riding on the table after an accumulation of impacts, y = z, ẏ = ż
  };
  static constexpr std::size_t max_witnesses = 1;
  static constexpr int wall = -1;  // the table, below the ball

  explicit BouncingBall(const BouncingBallParameters& p) : p_(p) {}

  [[nodiscard]] const BouncingBallParameters& parameters() const { return p_; }

  // table position (m), velocity (m/s) and acceleration (m/s²)
  // (over a number type, like the right-hand side). In double, sin ωt and
  // cos ωt are core/fast_trig.hpp's (an inline argument reduction, within a
  // few ulps of the library's), as a Taylor series' order 0 is: in a basins
  // grid on the exact flow the library's had been over half the time
  // (docs/performance.md).
  template <class Number>
  [[nodiscard]] Number table_position(const Number& t) const {
    return p_.A * sin_phase(p_.omega * t);
  }
  template <class Number>
  [[nodiscard]] Number table_velocity(const Number& t) const {
    return p_.A * p_.omega * cos_phase(p_.omega * t);
  }
  template <class Number>
  [[nodiscard]] Number table_acceleration(const Number& t) const {
    return -p_.A * p_.omega * p_.omega * sin_phase(p_.omega * t);
  }

  // g + z̈ (m/s²): the table's push on a ball resting on it, per unit mass
  // (the normal force over the mass). Positive while the table presses the
  // ball; its rate (m/s³) is the second.
  template <class Number>
  [[nodiscard]] Number table_push(const Number& t) const { return p_.g + table_acceleration(t); }
  template <class Number>
  [[nodiscard]] Number table_push_rate(const Number& t) const {
    return -p_.A * p_.omega * p_.omega * p_.omega * cos_phase(p_.omega * t);
  }
  [[nodiscard]] double table_push_curvature(double t) const {
    return p_.A * p_.omega * p_.omega * p_.omega * p_.omega * sin_phase(p_.omega * t);
  }

  [[nodiscard]] double max_step() const { return 2.0 * std::numbers::pi / p_.omega / 16.0; }

  // written over a number type (double, or the Taylor stepper's series type)
  template <class Number>
  void rhs(Mode mode, const std::array<Number, 2>& x, std::array<Number, 2>& dxdt,
           const Number& t) const {
    dxdt[0] = x[1];
    dxdt[1] = mode == Mode::free ? Number(-p_.g) : table_acceleration(t);
  }

  [[nodiscard]] std::size_t witness_count(Mode) const { return 1; }

  [[nodiscard]] TriggerDirection trigger_direction(Mode, std::size_t) const {
    return TriggerDirection::falling;
  }

  // free:  the gap y − z (m), closing when it falls to zero
  // stuck: the push g + z̈ (m/s²); the ball leaves when it falls to zero
  template <class Number>
  [[nodiscard]] BasicWitnessSample<Number> witness(Mode mode, std::size_t,
                                                   const std::array<Number, 2>& x,
                                                   const Number& t) const {
    if (mode == Mode::free) return {x[0] - table_position(t), x[1] - table_velocity(t)};
    return {table_push(t), table_push_rate(t)};
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t, CrossingKind crossing, const State& x,
                                   double t, EventLog& log) const {
    if (mode == Mode::free) return on_table_reached(crossing, x, t, log);
    // the push only touched zero and stays upward: the ball stays on the table
    if (crossing == CrossingKind::grazing) return {x, Mode::stuck, t, false};
    const State released = on_table(t);
    log.record({t, EventKind::contact_end, wall, released[0], released[1], released[1]});
    return {released, Mode::free, t, false};
  }

  // The closed-form flow from (t0, x0) to t in `mode`, τ = t − t0:
  // free:  the parabola y = y0 + ẏ0 τ − g τ²/2, ẏ = ẏ0 − g τ;
  // stuck: the table's motion, y = y0 + z(t) − z(t0), ẏ = ẏ0 + ż(t) − ż(t0)
  //        (exactly the solution of the stuck mode's ẏ' = z̈ from x0).
  void exact_flow(Mode mode, const State& x0, double t0, double t, State& x) const {
    const double tau = t - t0;
    if (mode == Mode::free) {
      x[0] = x0[0] + tau * (x0[1] - 0.5 * p_.g * tau);
      x[1] = x0[1] - p_.g * tau;
      return;
    }
    x[0] = x0[0] + (table_position(t) - table_position(t0));
    x[1] = x0[1] + (table_velocity(t) - table_velocity(t0));
  }

  // --- linearisation (core/has_jacobian.hpp), on (y, ẏ) ---

  // The flow of both modes is affine in the initial state (a parabola, the
  // table's motion), so the exact flow also gives its Jacobian.
  static constexpr bool affine_flow = true;

  // both modes: ∂(ẏ, ÿ)/∂(y, ẏ) = [[0, 1], [0, 0]] (ÿ is −g or z̈(t))
  void jacobian(Mode, const State&, double, TangentMatrix& j) const {
    j = {{{0.0, 1.0}, {0.0, 0.0}}};
  }

  // free: the gap y − z(t); stuck: the push depends on t alone
  [[nodiscard]] TangentVector witness_gradient(Mode mode, std::size_t, const State&,
                                               double) const {
    if (mode == Mode::stuck) return {0.0, 0.0};
    return {1.0, 0.0};
  }

  // the stuck mode pins the ball to the table
  [[nodiscard]] bool pinned(Mode mode) const { return mode == Mode::stuck; }

  // An impact sets y⁺ = z(t), ẏ⁺ = (1 + r) ż(t) − r ẏ⁻: ∂g/∂x = [[0, 0], [0, −r]]
  // and, because the table moves, ∂g/∂t = (ż, (1 + r) z̈). A grazing touch
  // leaves the state alone; an accumulation and a release collapse nearby
  // states into one.
  [[nodiscard]] ResetJacobian reset_jacobian(Mode mode, std::size_t, CrossingKind crossing,
                                             const State&, double t,
                                             const Transition<State, Mode>& after) const {
    if (crossing == CrossingKind::grazing) return identity_reset();
    if (mode == Mode::stuck || after.mode == Mode::stuck || after.time > t)
      return collapsed_reset();
    ResetJacobian reset = restitution_reset(p_.r);
    reset.time = {table_velocity(t), (1.0 + p_.r) * table_acceleration(t)};
    return reset;
  }

 private:
  // the ball resting on the table at t
  [[nodiscard]] State on_table(double t) const { return {table_position(t), table_velocity(t)}; }

  // An impact (or a grazing touch) on the table; then either flight again,
  // or, when the impacts are accumulating, a jump to their limit and riding.
  Transition<State, Mode> on_table_reached(CrossingKind crossing, const State& x, double t,
                                           EventLog& log) const {
    if (crossing == CrossingKind::grazing) {
      log.record({t, EventKind::grazing, wall, x[0], x[1], x[1]});
      return {x, Mode::free, t, false};
    }
    // Newton's law on the relative velocity γ_N = ẏ − ż (unit Jacobian, no friction)
    const double table_speed = table_velocity(t);
    const NewtonImpactResult impact =
        newton_impact(x[1] - table_speed, 1.0, 1.0, 0.0, 0.0, p_.r, 0.0);
    const double ydot_after = table_speed + impact.qdot_after;
    log.record({t, EventKind::impact, wall, x[0], x[1], ydot_after});
    const State after{table_position(t), ydot_after};

    // chattering: is the table pushing the ball back, and is the accumulation
    // estimate good? (with g + z̈ <= 0 the table pulls away: the ball is free)
    const auto estimate = accept_accumulation(
        {std::fabs(impact.qdot_after), table_push(t), table_push_rate(t), p_.r,
         table_push_curvature(t)},
        p_.accumulation);
    if (!estimate) return {after, Mode::free, t, false};
    return enter_stuck(t + estimate->remaining, estimate->error_bound, log);
  }

  // At the accumulation point the ball rides on the table if the table pushes
  // it; otherwise it leaves the table with the table's velocity. The records
  // carry the ball's state there, which is the table's (q = z, q̇ = ż).
  Transition<State, Mode> enter_stuck(double t, double time_error, EventLog& log) const {
    const State riding = on_table(t);
    EventRecord accumulation{t, EventKind::accumulation, wall, riding[0], riding[1], riding[1]};
    accumulation.accumulation_error = time_error;
    log.record(accumulation);
    if (!(table_push(t) > 0.0)) return {riding, Mode::free, t, false};
    log.record({t, EventKind::contact_start, wall, riding[0], riding[1], riding[1]});
    return {riding, Mode::stuck, t, false};
  }

  BouncingBallParameters p_;
};

static_assert(HybridSystem<BouncingBall>);
static_assert(HasJacobian<BouncingBall>);
static_assert(HasExactFlow<BouncingBall>);

}  // namespace impactlab
