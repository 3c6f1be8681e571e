// The stepper concept the event loop (simulate/simulator.hpp) drives: one
// accepted step at a time, never past a limit, with dense output inside the
// last step. Every stepper of integrate/ is checked against it where it is
// bound to the loop (simulate/flow_engines.hpp), so a stepper that lacks a
// member fails there with the member named, not deep inside the loop.
#pragma once

#include <concepts>
#include <cstddef>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/event_location.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

// A stepper's two flags: its static members has_cheap_scan and has_polish,
// or, for a stepper behind a view (simulate/stepper_view.hpp), the view's.
template <class Stepper>
constexpr bool scans_cheaply(const Stepper& stepper) {
  if constexpr (requires { stepper.scans_cheaply(); })
    return stepper.scans_cheaply();
  else
    return Stepper::has_cheap_scan;
}

template <class Stepper>
constexpr bool polishes(const Stepper& stepper) {
  if constexpr (requires { stepper.polishes(); })
    return stepper.polishes();
  else
    return Stepper::has_polish;
}

// ModeRhs<System> (integrate/stepper_settings.hpp) is the right-hand side of
// one mode as Boost.Odeint calls it, rhs(x, dxdt, t).

template <class Stepper, class System>
concept DenseOutputStepper =
    HybridSystem<System> &&
    requires(Stepper& stepper, const ModeRhs<System>& rhs,
             const typename System::State& x, typename System::State& out, double t) {
      // scan_state is cheaper than state_at (the event scan samples with it)
      { scans_cheaply(stepper) } -> std::convertible_to<bool>;
      // polish_state re-takes the step to an event time (more accurate than
      // state_at); the loop calls it where the stepper polishes
      { polishes(stepper) } -> std::convertible_to<bool>;
      { stepper.initialize(rhs, x, t, t) };  // restart at (t, x) with a first step
      { stepper.do_step(rhs, t) };           // one accepted step, never past the limit
      { stepper.state_at(rhs, t, out) };        // dense output inside the last step
      { stepper.scan_state(rhs, t, out) };
      { stepper.polish_state(rhs, t, out) };
      { stepper.previous_time() } -> std::convertible_to<double>;
      { stepper.current_time() } -> std::convertible_to<double>;
      { stepper.previous_state() } -> std::convertible_to<const typename System::State&>;
      { stepper.current_state() } -> std::convertible_to<const typename System::State&>;
      { stepper.suggested_step() } -> std::convertible_to<double>;
    };

// A stepper whose dense output is a polynomial locates the events of a step
// on it itself (integrate/taylor_stepper.hpp); the loop scans the others'
// (integrate/event_location.hpp). A view of steppers of both kinds
// (simulate/stepper_view.hpp) says which it is with locates_own_events().
template <class Stepper, class System>
concept LocatesItsOwnEvents =
    HybridSystem<System> &&
    requires(Stepper& stepper, const System& system, typename System::Mode mode, double t,
             const EventLocationOptions& options, std::size_t just_grazed) {
      { stepper.locate_first_event(system, mode, t, t, options, just_grazed) }
          -> std::convertible_to<LocatedEvent>;
    };

template <class Stepper, class System>
concept AlwaysLocatesItsOwnEvents =
    LocatesItsOwnEvents<Stepper, System> &&
    !requires(const Stepper& stepper) { stepper.locates_own_events(); };

}  // namespace impactlab
