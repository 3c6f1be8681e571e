// How a run of the event loop (simulate/simulator.hpp) ended, apart from the
// loop itself: the results that report it (io/run_output.hpp, the analyses)
// include this header alone.
#pragma once

#include <string_view>

namespace impactlab {

enum class Termination {
  completed,        // reached the end time
  stopped_by_model, // the system asked to stop (for example a Painlevé diagnostic)
  no_progress,      // the Zeno guard fired, or a witness went past zero by
                    // more than the tolerance with no event found (hops below
                    // round-off): an accumulation the model did not resolve
  frozen_time,      // t + step == t: time can no longer advance in a double
  non_finite_state, // a component of the state became inf or NaN
  step_budget,      // the run took LoopOptions::step_budget steps without reaching the end
  integrator_failure,  // the stepper could not take a step (its error control gave up,
                       // a GSL routine failed): an exception from do_step
  no_tangent_map,      // set by the analyses, not the loop: a linearisation they
                       // would report (multipliers, Lyapunov exponents) crosses an
                       // event whose tangent map is one-sided (an impulse on the
                       // friction cone's edge: Transition::one_sided)
};

constexpr std::string_view to_string(Termination termination) {
  switch (termination) {
    case Termination::completed: return "completed";
    case Termination::stopped_by_model: return "stopped_by_model";
    case Termination::no_progress: return "no_progress";
    case Termination::frozen_time: return "frozen_time";
    case Termination::non_finite_state: return "non_finite_state";
    case Termination::step_budget: return "step_budget";
    case Termination::integrator_failure: return "integrator_failure";
    case Termination::no_tangent_map: return "no_tangent_map";
  }
  return "unknown";
}

}  // namespace impactlab
