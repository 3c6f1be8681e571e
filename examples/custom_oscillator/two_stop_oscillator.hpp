// A harmonically forced linear oscillator between two rigid stops, defined
// outside the impactlab source tree (docs/extending.md walks through it):
//     free flight   ẍ + 2ζẋ + x = A cos ωt,   −d < x < d
//     either stop   x = ±d, Newton impact ẋ⁺ = −r ẋ⁻
// Units: non-dimensional, as oscillators/linear_impact: time in 1/ω_n, ω the
// forcing frequency over ω_n, x, A and d in one length unit.
//
// One mode only: the mass never rests on a stop. A run that reaches an
// accumulation of impacts (chatter) is stopped by the event loop's Zeno guard
// (Termination::no_progress); oscillators/linear_impact/linear_impact.hpp
// shows how to resolve one with contact/accumulation.hpp and a sticking mode.
// State: {x, ẋ}.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/core/hybrid_system.hpp>

namespace two_stop {

struct Parameters {
  double zeta = 0.05;  // damping ratio ζ (dimensionless), >= 0
  double A = 1.0;      // forcing amplitude (length)
  double omega = 2.0;  // forcing frequency over the natural frequency (dimensionless), > 0
  double gap = 0.25;   // half the distance between the stops d (length), > 0
  double r = 0.8;      // coefficient of restitution, [0, 1]
};

class TwoStopOscillator {
 public:
  using State = std::array<double, 2>;  // {x (length), ẋ (length per unit time)}
  enum class Mode { free };
  static constexpr std::size_t max_witnesses = 2;
  // witness index → the stop it watches, and the wall number events.csv uses
  static constexpr std::size_t right_stop = 0;  // x = +d, wall +1
  static constexpr std::size_t left_stop = 1;   // x = −d, wall −1

  explicit TwoStopOscillator(const Parameters& p) : p_(p) {}

  [[nodiscard]] const Parameters& parameters() const { return p_; }

  // A sixteenth of the shorter of the forcing and natural periods, so that the
  // event locator samples every extremum of the gaps.
  [[nodiscard]] double max_step() const {
    return 2.0 * std::numbers::pi / std::max(p_.omega, 1.0) / 16.0;
  }

  void rhs(Mode, const State& x, State& dxdt, double t) const {
    dxdt[0] = x[1];
    dxdt[1] = p_.A * std::cos(p_.omega * t) - 2.0 * p_.zeta * x[1] - x[0];
  }

  [[nodiscard]] std::size_t witness_count(Mode) const { return 2; }

  // Both gaps close: an event is a gap falling to zero.
  [[nodiscard]] impactlab::TriggerDirection trigger_direction(Mode, std::size_t) const {
    return impactlab::TriggerDirection::falling;
  }

  // The gap to each stop (length) and its rate along the flow.
  [[nodiscard]] impactlab::WitnessSample witness(Mode, std::size_t k, const State& x,
                                                 double) const {
    if (k == right_stop) return {p_.gap - x[0], -x[1]};
    return {x[0] + p_.gap, x[1]};
  }

  // An impact puts the mass on the stop with ẋ⁺ = −r ẋ⁻; a grazing touch
  // (ẋ⁻ = 0 to tolerance) leaves the state alone. (The event loop stops the
  // run itself on an unresolved crossing before asking the system.)
  impactlab::Transition<State, Mode> on_event(Mode mode, std::size_t k,
                                              impactlab::CrossingKind crossing, const State& x,
                                              double t, impactlab::EventLog& log) const {
    const int wall = k == right_stop ? 1 : -1;
    if (crossing == impactlab::CrossingKind::grazing) {
      log.record({t, impactlab::EventKind::grazing, wall, x[0], x[1], x[1]});
      return {x, mode, t, false};
    }
    const double velocity_after = -p_.r * x[1];
    log.record({t, impactlab::EventKind::impact, wall, wall * p_.gap, x[1], velocity_after});
    return {{wall * p_.gap, velocity_after}, mode, t, false};
  }

  // --- linearisation (core/has_jacobian.hpp), for saltation matrices and
  // Floquet multipliers ---

  // ∂(ẋ, ẍ)/∂(x, ẋ) = [[0, 1], [−1, −2ζ]]
  void jacobian(Mode, const State&, double, impactlab::TangentMatrix& j) const {
    j = {{{0.0, 1.0}, {-1.0, -2.0 * p_.zeta}}};
  }

  // ∂(gap)/∂(x, ẋ): d − x gives (−1, 0), x + d gives (+1, 0)
  [[nodiscard]] impactlab::TangentVector witness_gradient(Mode, std::size_t k, const State&,
                                                          double) const {
    if (k == right_stop) return {-1.0, 0.0};
    return {1.0, 0.0};
  }

  // x⁺ = ±d, ẋ⁺ = −r ẋ⁻: ∂g/∂x = [[0, 0], [0, −r]]; a grazing touch or a
  // stopped run leaves the state alone
  [[nodiscard]] impactlab::ResetJacobian reset_jacobian(
      Mode, std::size_t, impactlab::CrossingKind crossing, const State&, double,
      const impactlab::Transition<State, Mode>& after) const {
    if (crossing != impactlab::CrossingKind::crossing || after.stop)
      return impactlab::identity_reset();
    return impactlab::restitution_reset(p_.r);
  }

  // no mode pins the mass to a stop
  [[nodiscard]] bool pinned(Mode) const { return false; }

 private:
  Parameters p_;
};

static_assert(impactlab::HybridSystem<TwoStopOscillator>);
static_assert(impactlab::HasJacobian<TwoStopOscillator>);

}  // namespace two_stop
