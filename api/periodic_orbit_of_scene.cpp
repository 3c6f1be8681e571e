#include <impactlab/api/system_jobs.hpp>

#include <string>

#include <impactlab/analysis/run_periodic.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

PeriodicResult periodic_orbit_of_scene(const Scene& scene, const PeriodicRequest& request) {
  return visit_scene(scene, [&](const auto& bound) {
    if (std::string without = bound.without_linearisation(); !without.empty()) {
      PeriodicResult result;
      result.note = std::move(without);
      return result;
    }
    return run_periodic(bound.system(), bound.initial_state(), bound.flight_mode(), scene, request,
                        bound.forcing_frequency());
  });
}

}  // namespace impactlab
