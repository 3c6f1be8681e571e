// Newton shooting from a scene, for any oscillator (api/system_jobs.hpp): run a
// transient to the stroboscopic section, then locate the period-n orbit with
// the saltation-corrected monodromy (analysis/floquet.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/periodic.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/core/state_names.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

template <HybridSystem System>
PeriodicResult run_periodic(const System& system, const typename System::State& x0,
                            typename System::Mode mode0, const Scene& scene,
                            const PeriodicRequest& request, double omega) {
  PeriodicResult result;
  if constexpr (!HasJacobian<System>) {
    result.note = "this oscillator/model has no Jacobians";
    return result;
  } else {
    result.available = true;
    const FlowSetup setup = flow_setup(scene);
    SectionRequest size;  // the transient and one orbit, sized like a section run
    size.transient_periods = request.transient_periods + request.period;
    size.points = 0;
    check_section_size(size, omega, system.max_step(), setup.step_budget);
    const double period = 2.0 * std::numbers::pi / omega;
    const double t0 = scene.number("t0");
    // the first section time at or after the transient
    const double after = t0 + request.transient_periods * period;
    const double k = std::ceil((omega * after - request.phase) / (2.0 * std::numbers::pi) - 1e-9);
    result.t_section = (request.phase + 2.0 * std::numbers::pi * k) / omega;
    result.orbit_period = request.period * period;
    EventLog log(false);
    const auto transient =
        with_flow<System>(setup.method, stepper_settings(system, setup), [&](auto& stepper) {
          return simulate(system, stepper, x0, mode0, t0, result.t_section, loop_options(setup),
                          log);
        });
    if (transient.termination != Termination::completed) {
      result.termination = transient.termination;
      return result;
    }
    const auto orbit = locate_periodic_orbit(system, setup, transient.state, transient.mode,
                                             result.t_section, result.orbit_period,
                                             request.max_iterations, request.tolerance);
    result.state.assign(orbit.state.begin(), orbit.state.end());
    result.state_names = state_names_of(system);
    result.mode = static_cast<int>(orbit.mode);
    for (const auto& row : orbit.monodromy) result.monodromy.emplace_back(row.begin(), row.end());
    // an iterate that is not an orbit has no multipliers: none are written
    // (its monodromy, ∂Pⁿ/∂x at the state written, is kept for diagnosis)
    if (orbit.converged)
      result.multipliers.assign(orbit.multipliers.begin(), orbit.multipliers.end());
    result.converged = orbit.converged;
    result.iterations = orbit.iterations;
    result.residual = orbit.residual;
    result.termination = orbit.termination;
    result.failure = orbit.failure;
    return result;
  }
}

}  // namespace impactlab
