#include <impactlab/api/system_jobs.hpp>

#include <string>
#include <type_traits>
#include <vector>

#include <impactlab/analysis/run_periodic_orbits.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

PeriodicOrbitsResult periodic_orbits_of_scene(const Scene& scene,
                                              const PeriodicOrbitsRequest& request) {
  return visit_scene(scene, [&](const auto& bound) {
    if (std::string without = bound.without_linearisation(); !without.empty()) {
      PeriodicOrbitsResult result;
      result.note = std::move(without);
      return result;
    }
    // start s: the scene's initial state with each box key at its draw
    // (box_value at parameter index 0)
    using State = typename std::decay_t<decltype(bound)>::State;
    std::vector<State> starts;
    for (int s = 0; s < request.starts; ++s) {
      Scene sampled = scene;
      for (std::size_t k = 0; k < request.box.size(); ++k)
        sampled.values[request.box[k].key] =
            box_value(request.box[k], request.seed, 0, s, static_cast<int>(k));
      starts.push_back(bound.initial_state_of(sampled));
    }
    return run_periodic_orbits(bound.system(), starts, bound.flight_mode(), scene, request,
                               bound.forcing_frequency());
  });
}

}  // namespace impactlab
