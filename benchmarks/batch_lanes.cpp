// The batch lanes against one trajectory at a time (docs/performance.md,
// "Many trajectories at once"): the same sweep through the scene API with
// `batch` on (four lanes per thread, their Taylor series computed together)
// and off, on one thread. Two cases, as in the measurements of the docs:
//  * a periodic basins grid of jin2003 at V0 = 1.5 m/s, 8 × 8 initial states
//    (every lane the same system: the series share one pass);
//  * a 6 × 6 (ω, V0) map with the largest Lyapunov exponent (every lane its
//    own parameters: the series run one after the other).
// The records are the same with and without the batch (tests); only the time
// may differ. Arg 1: batch on, 0: off.
#include <vector>

#include <benchmark/benchmark.h>

#include <impactlab/api/basins_job.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/sweep_job.hpp>

namespace {

// Runs every task of `plan` on one thread per iteration, batch on where the
// benchmark's argument is 1; the counter `trajectories` is the records run.
void run_plan(benchmark::State& state, const impactlab::Scene& scene,
              const impactlab::SweepTarget& target, const impactlab::SweepPlan& plan) {
  const std::vector<impactlab::SweepTask> tasks = impactlab::sweep_tasks(plan);
  std::vector<const impactlab::SweepTask*> all;
  for (const auto& task : tasks) all.push_back(&task);
  impactlab::SweepJobOptions options;
  options.threads = 1;
  options.batch = state.range(0) != 0 ? "on" : "off";
  std::size_t records = 0;
  for (auto _ : state) {
    const impactlab::SweepOutput output = impactlab::run_sweep(scene, target, plan, all, options);
    records = 0;
    for (const auto& task_records : output.records) records += task_records.size();
    benchmark::DoNotOptimize(records);
  }
  state.counters["trajectories"] = static_cast<double>(records);
}

void BM_PeriodicBasinsGrid(benchmark::State& state) {
  impactlab::Scene scene = impactlab::load_scene("jin2003");
  scene.values["V0"] = 1.5;
  impactlab::BasinsSpec spec;
  spec.x = "initial.theta=-0.04:0.04:8";
  spec.y = "initial.theta_dot=-0.5:0.5:8";
  spec.section.transient_periods = 50;
  spec.section.points = 100;
  const impactlab::SweepTarget target = impactlab::sweep_target(scene);
  run_plan(state, scene, target, impactlab::make_basins_plan(spec, scene, *target.schema));
}
BENCHMARK(BM_PeriodicBasinsGrid)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_MapWithLyapunovExponents(benchmark::State& state) {
  const impactlab::Scene scene = impactlab::load_scene("jin2003");
  impactlab::SweepSpec spec;
  spec.params = {"omega=6:8:6", "V0=1:5:6"};
  const impactlab::SweepTarget target = impactlab::sweep_target(scene);
  run_plan(state, scene, target, impactlab::make_sweep_plan(spec, scene, *target.schema));
}
BENCHMARK(BM_MapWithLyapunovExponents)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
