// The one event loop: step with dense output, locate the earliest witness
// root in the step, move to it, apply the system's transition, restart the
// stepper cleanly, repeat until the end time.
//
// Guarantees:
// * an event exactly at t0 is applied before the first step (a state on a
//   wall and moving into it), and a root at exactly the end time is kept;
// * after an event the stepper restarts at the event, and a witness that sits
//   at zero there is not armed again until it has left zero, so the same
//   event is never found twice;
// * the loop itself allocates nothing and calls the right-hand side through a
//   template parameter (no virtual call per evaluation);
// * a run that makes no progress in time (an accumulation of events that the
//   model did not resolve) is stopped by the named Zeno guard, not left to hang;
// * a run whose time can no longer advance in a double (t + step == t, for
//   example t0 = 1e17 s), whose state becomes non-finite (inf or NaN), or that
//   has taken its whole step budget, stops with a termination that says so; it
//   never reports `completed`.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/event_location.hpp>
#include <impactlab/integrate/stepper_settings.hpp>
#include <impactlab/simulate/dense_output_stepper.hpp>
#include <impactlab/simulate/termination.hpp>

namespace impactlab {

// Guard against an unresolved accumulation of events (Zeno behaviour): if more
// than `max_events` events happen while time advances by less than `window`
// seconds, the run stops with Termination::no_progress.
struct ZenoGuard {
  std::uint64_t max_events = 10000;
  double window = 1e-6;  // s
};

// The most steps (accepted steps, one per event restart included) one call of
// simulate() may take before it stops with Termination::step_budget: every
// run is bounded, whatever its parameters. 10^9 steps is of the order of an
// hour of CPU time; callers that know their run's size pass a tighter budget.
constexpr std::uint64_t default_step_budget = 1'000'000'000;

struct LoopOptions {
  EventLocationOptions location;
  ZenoGuard zeno;
  std::uint64_t step_budget = default_step_budget;
};

// True when every component of the state is finite.
template <class State>
bool all_finite(const State& x) {
  return std::all_of(std::begin(x), std::end(x), [](double value) { return std::isfinite(value); });
}

struct RunCounters {
  std::uint64_t steps = 0;
  std::uint64_t rhs_evaluations = 0;
  std::uint64_t events = 0;
  std::uint64_t one_sided_events = 0;  // with a one-sided tangent map (Transition::one_sided)
};

template <class State, class Mode>
struct RunResult {
  State state{};
  Mode mode{};
  double t = 0.0;
  Termination termination = Termination::completed;
  RunCounters counters;
};

// Receives the state at requested times; the default requests none.
struct NoObserver {
  [[nodiscard]] double next_time() const { return INFINITY; }
  template <class State, class Mode>
  void observe(double, const State&, Mode) {}
};

template <HybridSystem System, class Stepper, class Observer = NoObserver>
RunResult<typename System::State, typename System::Mode> simulate(
    const System& system, Stepper& stepper, typename System::State x, typename System::Mode mode,
    double t0, double t_end, const LoopOptions& options, EventLog& log,
    Observer&& observer = Observer{}) {
  using State = typename System::State;
  RunResult<State, typename System::Mode> result;
  EventLocationOptions location = options.location;
  location.max_step = system.max_step();
  ModeRhs<System> rhs{&system, mode, &result.counters.rhs_evaluations};
  double t = t0;
  double zeno_checkpoint_time = t0;
  // why apply_event() stopped the run, when the system did not ask for it
  Termination stopped_by = Termination::stopped_by_model;
  std::uint64_t zeno_checkpoint_events = 0;

  auto emit_observations = [&](double up_to, auto&& state_at) {
    while (observer.next_time() <= up_to) {
      const double ts = observer.next_time();
      State xs;
      state_at(ts, xs);
      observer.observe(ts, xs, rhs.mode);
    }
  };
  auto finish = [&](Termination termination) {
    result.state = x;
    result.mode = rhs.mode;
    result.t = t;
    result.termination = termination;
    return result;
  };

  // Applies the transition of an event at (te, xe); false when the run stops.
  auto apply_event = [&](std::size_t witness, CrossingKind kind, double te, const State& xe) {
    ++result.counters.events;
    const auto transition = system.on_event(rhs.mode, witness, kind, xe, te, log);
    if (transition.one_sided) ++result.counters.one_sided_events;
    if (transition.stop) {
      t = te;
      x = transition.state;
      return false;
    }
    // a state or a restart time that is not finite (an impulse or an
    // accumulation's end computed from extreme parameters) ends the run as
    // such: never a NaN time that ends the loop as if it were complete
    if (!all_finite(transition.state) || !std::isfinite(transition.time)) {
      t = te;
      x = xe;
      stopped_by = Termination::non_finite_state;
      return false;
    }
    // the state between the event and a later restart time (an accumulation
    // jumped over) is the state the system continues from
    const double restart = std::min(std::max(transition.time, te), t_end);
    emit_observations(restart, [&](double, State& out) { out = transition.state; });
    t = restart;
    x = transition.state;
    rhs.mode = transition.mode;
    return true;
  };

  auto zeno_guard_fired = [&]() {
    if (t - zeno_checkpoint_time > options.zeno.window) {
      zeno_checkpoint_time = t;
      zeno_checkpoint_events = result.counters.events;
      return false;
    }
    return result.counters.events - zeno_checkpoint_events > options.zeno.max_events;
  };

  // A witness exactly at zero at the end time, having been armed at the start
  // of the last step and moving towards its trigger side, is an event at the
  // end time (its computed value may land on either side of zero by round-off).
  auto apply_event_at_end = [&](double t_step_start) {
    for (std::size_t k = 0; k < system.witness_count(rhs.mode); ++k) {
      const TriggerDirection direction = system.trigger_direction(rhs.mode, k);
      if (direction == TriggerDirection::either) continue;
      const double sign = direction == TriggerDirection::rising ? -1.0 : 1.0;
      const WitnessSample w = system.witness(rhs.mode, k, x, t);
      const double start_value =
          sign * system.witness(rhs.mode, k, stepper.previous_state(), t_step_start).value;
      const double value = sign * w.value;
      if (start_value > options.location.grazing_tolerance && value > 0.0 &&
          value <= options.location.grazing_tolerance && sign * w.rate < 0.0)
        return apply_event(k, CrossingKind::crossing, t, State(x));
    }
    return true;
  };

  // a time that is not a number (t0, or an end time computed from bad input)
  // is a non-finite state: no run, and never `completed`
  if (!std::isfinite(t0) || std::isnan(t_end)) return finish(Termination::non_finite_state);

  // events at t0: a witness at zero, moving towards its trigger side or not
  // moving at all (a state resting on a wall: the system decides whether it
  // stays in contact or leaves)
  for (std::size_t k = 0; k < system.witness_count(rhs.mode); ++k) {
    const WitnessSample w = system.witness(rhs.mode, k, x, t);
    const TriggerDirection direction = system.trigger_direction(rhs.mode, k);
    const bool at_zero = std::fabs(w.value) <= options.location.grazing_tolerance;
    const bool inward = direction == TriggerDirection::falling  ? w.rate <= 0.0
                        : direction == TriggerDirection::rising ? w.rate >= 0.0
                                                                : false;
    if (at_zero && inward) {
      if (!apply_event(k, CrossingKind::crossing, t, x)) return finish(stopped_by);
      break;
    }
  }
  if (!all_finite(x)) return finish(Termination::non_finite_state);
  emit_observations(t, [&](double, State& out) { out = x; });

  constexpr std::size_t no_witness = static_cast<std::size_t>(-1);
  std::size_t just_grazed = no_witness;  // witness whose grazing was the last event
  // time is frozen where a hundredth of the system's longest step is lost in
  // t's spacing, even for a span that itself rounded to nothing (t0 = 1e17 s
  // plus five forcing periods is t0 again)
  if (t + 0.01 * system.max_step() == t) return finish(Termination::frozen_time);
  const double first_step = std::min(0.01 * system.max_step(), t_end - t0);
  stepper.initialize(rhs, x, t, first_step);
  while (t < t_end) {
    if (result.counters.steps >= options.step_budget) return finish(Termination::step_budget);
    // Boost.Odeint gives up on a step after 500 rejections (step_adjustment_error),
    // the GSL stepper on a failed status: both std::runtime_error
    try {
      stepper.do_step(rhs, t_end);
    } catch (const std::runtime_error&) {
      return finish(Termination::integrator_failure);
    }
    ++result.counters.steps;
    const double ta = stepper.previous_time();
    const double tb = std::min(stepper.current_time(), t_end);
    if (!(tb > ta)) return finish(Termination::frozen_time);
    auto state_at = [&](double ts, State& out) { stepper.state_at(rhs, ts, out); };
    auto scan_at = [&](double ts, State& out) { stepper.scan_state(rhs, ts, out); };
    State x_end;
    if (tb == stepper.current_time())
      x_end = stepper.current_state();
    else
      state_at(tb, x_end);
    if (!all_finite(x_end)) return finish(Termination::non_finite_state);

    // a stepper whose dense output is a polynomial locates events on it
    // itself (integrate/taylor_stepper.hpp); the others are scanned
    const LocatedEvent event = [&] {
      if constexpr (AlwaysLocatesItsOwnEvents<Stepper, System>) {
        return stepper.locate_first_event(system, rhs.mode, ta, tb, location, just_grazed);
      } else {
        if constexpr (LocatesItsOwnEvents<Stepper, System>)
          if (stepper.locates_own_events())
            return stepper.locate_first_event(system, rhs.mode, ta, tb, location, just_grazed);
        return locate_first_event(system, rhs.mode, ta, tb, stepper.previous_state(), x_end,
                                  state_at, scan_at, scans_cheaply(stepper), location,
                                  just_grazed);
      }
    }();
    just_grazed = no_witness;
    if (!event.found) {
      emit_observations(tb, state_at);
      t = tb;
      x = x_end;
      if (t >= t_end && !apply_event_at_end(ta)) return finish(stopped_by);
      continue;
    }

    if (event.kind == CrossingKind::unresolved) {
      t = event.t;
      state_at(t, x);
      return finish(Termination::no_progress);
    }

    // the state at the event: the dense output, then (where the stepper can)
    // its own step re-taken to the event time with one Newton correction
    State xe;
    double te = event.t;
    if (polishes(stepper)) {
      stepper.polish_state(rhs, te, xe);
      const WitnessSample w = system.witness(rhs.mode, event.witness, xe, te);
      if (event.kind == CrossingKind::crossing && w.rate != 0.0) {
        const double corrected = te - w.value / w.rate;
        if (std::fabs(corrected - te) < 1e-3 * (tb - ta) && corrected > ta && corrected <= tb) {
          te = corrected;
          stepper.polish_state(rhs, te, xe);
        }
      }
    } else {
      state_at(te, xe);
    }
    emit_observations(te, state_at);
    const auto mode_before = rhs.mode;
    if (!apply_event(event.witness, event.kind, te, xe)) return finish(stopped_by);
    if (event.kind == CrossingKind::grazing && rhs.mode == mode_before) just_grazed = event.witness;
    if (zeno_guard_fired()) return finish(Termination::no_progress);
    stepper.initialize(rhs, x, t, stepper.suggested_step());
  }
  return finish(Termination::completed);
}

}  // namespace impactlab
