// How the analysis layer integrates a scene's system: the scene's own
// integrator method and tolerances (integrator.method, integrator.rtol,
// integrator.atol), turned into the settings the event loop takes, exactly as
// `impactlab simulate` does (api/run_system.hpp).
#pragma once

#include <cstdint>
#include <string>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

struct Scene;

struct FlowSetup {
  std::string method = "dopri5";  // integrator.method
  double rtol = 1e-10;            // integrator.rtol
  double atol = 1e-12;            // integrator.atol (state units)
  std::uint64_t step_budget = default_step_budget;  // limits.max_steps, per event-loop run
  // the batch lane whose Taylor steppers' series are computed together with
  // other lanes' (simulate/series_batch.hpp); none: each stepper its own
  SeriesLane* series_lane = nullptr;
};

// The scene's integrator keys and step budget.
FlowSetup flow_setup(const Scene& scene);

struct IntegratorSetting;

// The setup with another integrator (method, rtol, atol), the step budget kept.
FlowSetup with_integrator(FlowSetup setup, const IntegratorSetting& integrator);

// The scene's own integrator (integrator.method, integrator.rtol,
// integrator.atol).
IntegratorSetting scene_integrator(const Scene& scene);

template <HybridSystem System>
StepperSettings stepper_settings(const System& system, const FlowSetup& setup) {
  StepperSettings settings;
  settings.rtol = setup.rtol;
  settings.atol = setup.atol;
  settings.max_step = system.max_step();
  settings.series_lane = setup.series_lane;
  return settings;
}

inline LoopOptions loop_options(const FlowSetup& setup) {
  LoopOptions options;
  options.location.grazing_tolerance = setup.atol;
  options.step_budget = setup.step_budget;
  return options;
}

}  // namespace impactlab
