// The definition of continuation_of_binding (api/continuation_of_binding.hpp),
// included by the build's generated part units alone.
#pragma once

#include <string>
#include <utility>

#include <impactlab/analysis/run_continuation.hpp>
#include <impactlab/api/continuation_of_binding.hpp>

namespace impactlab {

template <class Binding>
ContinuationJobResult continuation_of_binding(const SceneSystem<Binding>& bound,
                                              const Scene& scene, const ContinuationJob& job) {
  using System = typename Binding::System;
  if (std::string without = bound.without_linearisation(); !without.empty()) {
    ContinuationJobResult result;
    result.note = std::move(without);
    return result;
  }
  const typename System::State x0 =
      job.has_start ? typename System::State{} : bound.initial_state();
  return run_continuation<System>(&SceneSystem<Binding>::system_at, bound.flight_mode(), x0, scene,
                                  job, SceneSystem<Binding>::boundaries());
}

}  // namespace impactlab
