// The landing of a contact phase, as an orbit notes it (OrbitEvaluation,
// continuation_problem.hpp): the instant a mass comes to rest on a wall
// (the accumulation point of a chatter, or a plastic impact, r = 0, that
// leaves it with zero normal speed), and the push into the wall on the mass
// at rest there: the contact phase's own release witness (the normal force
// per unit mass; the pendulum's in N), evaluated at that instant. The
// contact phase that starts there lasts while the push is positive; where it
// is not, the mass leaves at once. The push is smooth in the state and the parameters on both sides
// of zero, so its zero is the defining condition of a contact onset or end
// (the curves `contact_onset` and `contact_end`, curve_continuation.hpp):
// the mass lands exactly where the push falls through zero, i.e. it returns
// to the wall at the release time.
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/core/event_log.hpp>

namespace impactlab {

// A system whose contact phase is one mode named `stuck` (the mass resting on
// its stop or table: the linear impact oscillator, the bouncing ball), whose
// witness 0 is the push into the wall, and whose flight mode `free` has the
// wall's gap as witness 0 (its rate: the normal speed relative to the wall).
// Others note no landing push.
template <class System>
concept HasStuckMode = requires {
  System::Mode::stuck;
  System::Mode::free;
};

// A system that says itself which events are landings and the push there
// (the pendulum, whose contact phases are one mode per wall):
// landing_push(event) is the contact phase's release witness at the event
// where it is a landing, none where it is not.
template <class System>
concept HasLandingPush = requires(const System& system, const EventRecord& event) {
  { system.landing_push(event) } -> std::convertible_to<std::optional<double>>;
};

// The landing among the records [begin, end) whose push on the mass at rest
// is nearest zero, into result.landing_push and result.landing_time (since
// t0, s); left NaN where the system has neither a stuck mode nor
// landing_push, or the orbit no landing.
template <class System, class Records>
void note_landing_push(const System& system, Records begin, Records end, double t0,
                       OrbitEvaluation& result) {
  const auto take = [&](double push, double t) {
    if (!(std::fabs(push) < std::fabs(result.landing_push)) && std::isfinite(result.landing_push))
      return;
    result.landing_push = push;
    result.landing_time = t - t0;
  };
  if constexpr (HasLandingPush<System>) {
    for (auto event = begin; event != end; ++event)
      if (const std::optional<double> push = system.landing_push(*event)) take(*push, event->t);
  } else if constexpr (HasStuckMode<System>) {
    for (auto event = begin; event != end; ++event) {
      // a plastic impact leaves the mass at zero speed relative to the wall
      // (a fixed stop: q̇ = 0; a moving table: ẏ = ż)
      typename System::State after{};
      after[0] = event->q;
      after[1] = event->qdot_after;
      const bool plastic =
          event->kind == EventKind::impact &&
          system.witness(System::Mode::free, 0, after, event->t).rate == 0.0;
      if (!plastic && event->kind != EventKind::accumulation) continue;
      // at rest on the wall: position q on it, zero rate (the stuck mode's
      // push of these systems depends on time alone)
      typename System::State rest{};
      rest[0] = event->q;
      take(system.witness(System::Mode::stuck, 0, rest, event->t).value, event->t);
    }
  }
}

}  // namespace impactlab
