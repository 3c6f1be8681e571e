#include "api/scene_jobs.hpp"

#include "api/oscillator_registry.hpp"
#include "io/bad_input.hpp"

namespace impactlab {

RunOutput simulate(const Scene& scene, const RunRequest& request) {
  return oscillator_entry(scene.oscillator).run(scene, request);
}

SectionResult poincare(const Scene& scene, const SectionRequest& request) {
  const OscillatorEntry& entry = oscillator_entry(scene.oscillator);
  if (!entry.section)
    throw BadInput("oscillator", scene.oscillator, "has no Poincare-section entry");
  return entry.section(scene, request);
}

PeriodicResult periodic(const Scene& scene, const PeriodicRequest& request) {
  const OscillatorEntry& entry = oscillator_entry(scene.oscillator);
  if (!entry.periodic_orbit)
    throw BadInput("oscillator", scene.oscillator, "has no periodic-orbit entry");
  return entry.periodic_orbit(scene, request);
}

SweepTarget sweep_target(const Scene& scene) {
  const OscillatorEntry& entry = oscillator_entry(scene.oscillator);
  if (!entry.section)
    throw BadInput("oscillator", scene.oscillator, "has no Poincare-section entry");
  return {entry.schema, entry.section};
}

}  // namespace impactlab
