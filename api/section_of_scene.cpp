#include <impactlab/api/system_jobs.hpp>

#include <limits>
#include <string>
#include <type_traits>

#include <impactlab/analysis/run_section.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

SectionResult section_of_scene(const Scene& scene, const SectionRequest& request) {
  return visit_scene(scene, [&]<class Binding>(const SceneSystem<Binding>& bound) {
    // a continued run does not start from the scene's initial state (which a
    // swept key may have made inadmissible)
    const auto x0 = request.start ? typename SceneSystem<Binding>::State{} : bound.initial_state();
    const std::string without = bound.without_linearisation();
    if ((request.lyapunov || request.lyapunov_spectrum) && !without.empty()) {
      SectionRequest plain = request;
      plain.lyapunov = false;
      plain.lyapunov_spectrum = false;
      SectionResult result = run_section(bound.system(), x0, bound.flight_mode(), scene, plain,
                                         bound.forcing_frequency(), bound.admissible());
      if (request.lyapunov) result.lyapunov_note = without;
      if (request.lyapunov_spectrum) {
        // N exponents, none of them computed
        using System = std::remove_cvref_t<decltype(bound.system())>;
        result.lyapunov_spectrum.assign(tangent_dimension_of<System>,
                                        std::numeric_limits<double>::quiet_NaN());
        result.lyapunov_spectrum_error = result.lyapunov_spectrum;
        result.lyapunov_spectrum_note = without;
      }
      return result;
    }
    return run_section(bound.system(), x0, bound.flight_mode(), scene, request,
                       bound.forcing_frequency(), bound.admissible());
  });
}

}  // namespace impactlab
