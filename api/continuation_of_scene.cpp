#include <impactlab/api/system_jobs.hpp>

#include <string>

#include <impactlab/analysis/run_continuation.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

ContinuationJobResult continuation_of_scene(const Scene& scene, const ContinuationJob& job) {
  return visit_scene(scene, [&]<class Binding>(const SceneSystem<Binding>& bound) {
    using System = typename Binding::System;
    if (std::string without = bound.without_linearisation(); !without.empty()) {
      ContinuationJobResult result;
      result.note = std::move(without);
      return result;
    }
    const typename System::State x0 =
        job.has_start ? typename System::State{} : bound.initial_state();
    return run_continuation<System>(&SceneSystem<Binding>::system_at, bound.flight_mode(), x0,
                                    scene, job, SceneSystem<Binding>::boundaries());
  });
}

}  // namespace impactlab
