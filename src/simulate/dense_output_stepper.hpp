// The stepper concept the event loop (simulate/simulator.hpp) drives: one
// accepted step at a time, never past a limit, with dense output inside the
// last step. Every stepper of integrate/ is checked against it where it is
// bound to the loop (simulate/flow_engines.hpp), so a stepper that lacks a
// member fails there with the member named, not deep inside the loop.
#pragma once

#include <concepts>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

// ModeRhs<System> (integrate/stepper_settings.hpp) is the right-hand side of
// one mode as Boost.Odeint calls it, rhs(x, dxdt, t).

template <class Stepper, class System>
concept DenseOutputStepper =
    HybridSystem<System> &&
    requires(Stepper& stepper, const ModeRhs<System>& rhs,
             const typename System::State& x, typename System::State& out, double t) {
      // scan_state is cheaper than state_at (the event scan samples with it)
      { Stepper::has_cheap_scan } -> std::convertible_to<bool>;
      // polish_state re-takes the step to an event time (more accurate than state_at)
      { Stepper::has_polish } -> std::convertible_to<bool>;
      { stepper.initialize(rhs, x, t, t) };  // restart at (t, x) with a first step
      { stepper.do_step(rhs, t) };           // one accepted step, never past the limit
      { stepper.state_at(rhs, t, out) };        // dense output inside the last step
      { stepper.scan_state(rhs, t, out) };
      { stepper.previous_time() } -> std::convertible_to<double>;
      { stepper.current_time() } -> std::convertible_to<double>;
      { stepper.previous_state() } -> std::convertible_to<const typename System::State&>;
      { stepper.current_state() } -> std::convertible_to<const typename System::State&>;
      { stepper.suggested_step() } -> std::convertible_to<double>;
    };

}  // namespace impactlab
