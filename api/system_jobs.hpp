// The analyses run on a scene's system, whatever its oscillator: each visits
// the scene's binding (api/visit_scene.hpp) and runs the generic analysis of
// analysis/ on the system it builds. One translation unit per analysis
// (api/<analysis>_of_scene.cpp), each compiled once for every binding; the
// continuation, too large for one unit, in parts (api/binding_parts.hpp).
// api/scene_jobs.hpp adds the checks of the jobs' options on top.
#pragma once

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/periodic.hpp>
#include <impactlab/analysis/periodic_orbits.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/io/event_columns.hpp>
#include <impactlab/io/event_extension.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// One event-driven run (events, samples, counters, the binding's derived
// quantities).
RunOutput run_of_scene(const Scene& scene, const RunRequest& request);

// What the events of the scene's model add to the core's record (the
// pendulum's Model P: its impact residuals); empty where nothing.
EventExtender event_extender_of_scene(const Scene& scene);
// events.csv's columns beyond the core's that the scene's model fills
EventColumns event_columns_of_scene(const Scene& scene);

// The orbit on a Poincaré section, after a transient (analysis/run_section.hpp).
SectionResult section_of_scene(const Scene& scene, const SectionRequest& request);

// Newton shooting for a period-n orbit and its Floquet multipliers
// (analysis/run_periodic.hpp).
PeriodicResult periodic_orbit_of_scene(const Scene& scene, const PeriodicRequest& request);

// Every period-n orbit that deflated Newton shooting finds from the request's
// starts, drawn from its box (analysis/run_periodic_orbits.hpp).
PeriodicOrbitsResult periodic_orbits_of_scene(const Scene& scene,
                                              const PeriodicOrbitsRequest& request);

// Pseudo-arclength continuation of a period-n orbit, its bifurcations and
// grazing points (analysis/run_continuation.hpp).
ContinuationJobResult continuation_of_scene(const Scene& scene, const ContinuationJob& job);

}  // namespace impactlab
