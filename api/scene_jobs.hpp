// The scene API's jobs: what a front end (the CLI, the Python module, a
// user's program) asks of a loaded scene. Each looks up the scene's
// oscillator in the registry and runs its binding, so every front end gets
// the same validation, the same numbers and the same errors.
#pragma once

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/periodic.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/analysis/sweep.hpp>
#include <impactlab/io/event_columns.hpp>
#include <impactlab/io/event_extension.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// One event-driven run of the scene (events, samples, counters).
RunOutput simulate(const Scene& scene, const RunRequest& request);

// What the events of the scene's model add to the core's record, for the
// events writer and Python's events array (io/event_extension.hpp); empty
// where nothing (every model but the pendulum's Model P).
EventExtender event_extender(const Scene& scene);
// events.csv's columns of a run of the scene: the core's and its model's own
EventColumns event_columns(const Scene& scene);

// The scene's orbit on a Poincaré section. BadInput (key `oscillator`) when
// the scene's oscillator or model has no section binding.
SectionResult poincare(const Scene& scene, const SectionRequest& request);

// Newton shooting for a period-n orbit and its Floquet multipliers. BadInput
// (key `oscillator`) when the scene's oscillator or model has none.
PeriodicResult periodic(const Scene& scene, const PeriodicRequest& request);

// Pseudo-arclength continuation of a period-n orbit in job.parameter from
// job.from to job.to, its bifurcations and grazing points, and with
// job.doublings the doubled orbits. BadInput when the key is not a numeric
// parameter of the oscillator or one its model does not read
// (api/model_keys.hpp; key `param`, `param2` for the second), an end
// of the range is out of the key's range, the oscillator or model has no
// Jacobians (key `oscillator`), or no orbit converges at the start (key
// `param`). Options are named by their own names (api/job_options.hpp).
ContinuationJobResult continue_orbit(const Scene& scene, const ContinuationJob& job);

// The section of a continuation from its text (`strobe[:PHASE]` or
// `impact:WALL`, WALL +1 or -1) into job.phase / job.impact_wall; BadInput
// (key `key`) for another section or impact:0 (any wall).
void set_continuation_section(ContinuationJob& job, const std::string& text,
                              const std::string& key);

// What a sweep of the scene runs at each point: its schema and its section
// binding. BadInput (key `oscillator`) when it has no section binding.
SweepTarget sweep_target(const Scene& scene);

}  // namespace impactlab
