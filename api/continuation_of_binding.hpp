// A continuation job on one binding's system (api/system_jobs.hpp's
// continuation_of_scene visits the scene's binding and calls it). Declared
// here, defined in api/continuation_of_binding_definition.hpp and compiled in
// parts (api/binding_parts.hpp): compiled for every binding in one unit, it
// was the build's largest.
#pragma once

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/api/scene_system.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

template <class Binding>
ContinuationJobResult continuation_of_binding(const SceneSystem<Binding>& bound,
                                              const Scene& scene, const ContinuationJob& job);

}  // namespace impactlab
