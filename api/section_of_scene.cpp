#include <impactlab/api/system_jobs.hpp>

#include <string>

#include <impactlab/analysis/run_section.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

SectionResult section_of_scene(const Scene& scene, const SectionRequest& request) {
  return visit_scene(scene, [&]<class Binding>(const SceneSystem<Binding>& bound) {
    // a continued run does not start from the scene's initial state (which a
    // swept key may have made inadmissible)
    const auto x0 = request.start ? typename SceneSystem<Binding>::State{} : bound.initial_state();
    const std::string without = bound.without_linearisation();
    if (request.lyapunov && !without.empty()) {
      SectionRequest plain = request;
      plain.lyapunov = false;
      SectionResult result = run_section(bound.system(), x0, bound.flight_mode(), scene, plain,
                                         bound.forcing_frequency(), bound.admissible());
      result.lyapunov_note = without;
      return result;
    }
    return run_section(bound.system(), x0, bound.flight_mode(), scene, request,
                       bound.forcing_frequency(), bound.admissible());
  });
}

}  // namespace impactlab
