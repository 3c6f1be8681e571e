#include <impactlab/api/system_jobs.hpp>

#include <impactlab/api/continuation_of_binding.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

ContinuationJobResult continuation_of_scene(const Scene& scene, const ContinuationJob& job) {
  return visit_scene(scene, [&]<class Binding>(const SceneSystem<Binding>& bound) {
    return continuation_of_binding(bound, scene, job);
  });
}

}  // namespace impactlab
