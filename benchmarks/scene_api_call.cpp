// The cost of one scene-API call from C++, for the Python module's per-call
// overhead (docs/performance.md, "From Python"): a tiny run of the jin2003
// scene (0.01 forcing periods), and the same run plus the scene copy that
// impactlab.simulate makes of a Scene passed to it.
#include <benchmark/benchmark.h>

#include "api/scene_jobs.hpp"
#include "api/scene_loading.hpp"

namespace {

impactlab::RunRequest tiny_request() {
  impactlab::RunRequest request;
  request.periods = 0.01;
  return request;
}

void BM_SimulateTinyRun(benchmark::State& state) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const impactlab::RunRequest request = tiny_request();
  for (auto _ : state) benchmark::DoNotOptimize(impactlab::simulate(scene, request));
}
BENCHMARK(BM_SimulateTinyRun);

void BM_SimulateTinyRunWithSceneCopy(benchmark::State& state) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const impactlab::RunRequest request = tiny_request();
  for (auto _ : state) {
    const impactlab::Scene copy = scene;
    benchmark::DoNotOptimize(impactlab::simulate(copy, request));
  }
}
BENCHMARK(BM_SimulateTinyRunWithSceneCopy);

}  // namespace
