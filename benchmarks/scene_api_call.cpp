// The cost of one scene-API call from C++, for the Python module's per-call
// overhead (docs/performance.md, "From Python"): a tiny run of the jin2003
// scene (0.01 forcing periods) without and with a progress callback (the
// Python module, like the CLI, always passes one: it is where Ctrl-C is
// looked for), and the run plus a scene copy.
#include <benchmark/benchmark.h>

#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>

namespace {

impactlab::RunRequest tiny_request() {
  impactlab::RunRequest request;
  request.periods = 0.01;
  return request;
}

void BM_SimulateTinyRun(benchmark::State& state) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  const impactlab::RunRequest request = tiny_request();
  impactlab::RunOutput output;
  for (auto _ : state) {
    output = impactlab::simulate(scene, request);
    benchmark::DoNotOptimize(output);
  }
  // the run's own work, to set beside the same counters from Python
  state.counters["rhs_evaluations"] = static_cast<double>(output.rhs_evaluations);
  state.counters["loop_wall_us"] = output.wall_time * 1e6;
}
BENCHMARK(BM_SimulateTinyRun);

// The call as the CLI and the Python module make it: with a progress
// callback, which the run calls at each hundredth (99 dense-output
// evaluations of the state, rkf78: about 12 right-hand sides each).
void BM_SimulateTinyRunWithProgress(benchmark::State& state) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  impactlab::RunRequest request = tiny_request();
  double last_fraction = 0.0;
  request.progress = [&last_fraction](double fraction) { last_fraction = fraction; };
  impactlab::RunOutput output;
  for (auto _ : state) {
    output = impactlab::simulate(scene, request);
    benchmark::DoNotOptimize(output);
  }
  benchmark::DoNotOptimize(last_fraction);
  state.counters["rhs_evaluations"] = static_cast<double>(output.rhs_evaluations);
  state.counters["loop_wall_us"] = output.wall_time * 1e6;
}
BENCHMARK(BM_SimulateTinyRunWithProgress);

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
