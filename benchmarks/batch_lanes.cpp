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
// And the Taylor series alone, of one trajectory and of a pass over lanes.
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include <impactlab/api/basins_job.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/sweep_job.hpp>
#include <impactlab/integrate/series_tape.hpp>
#include <impactlab/integrate/taylor_series.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>

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

// The series alone, at the order of jin2003's tolerance (rtol 1e-12: 22), of
// a forced pendulum between two walls, θ'' = −0.01 θ' − (9.81 − 10.5 cos 7t)
// sin θ / 0.7 with the walls' witnesses 0.3 ∓ θ, in the form of the
// steppers' right-hand sides; a third state of zero rate stands for the
// pendulum's third state (its friction work, constant in flight): what a
// batch saves on the series (docs/performance.md, "What 3× would take").
struct ForcedPendulumSeriesRhs {
  template <class Variables, class Time, class Outputs>
  int operator()(const Variables& x, const Time& t, Variables& dxdt, Outputs& witnesses) const {
    using std::cos;
    using std::sin;
    dxdt[0] = x[1];
    dxdt[1] = -0.01 * x[1] - (9.81 - 10.5 * cos(7.0 * t)) * sin(x[0]) / 0.7;
    dxdt[2] = 0.0 * x[1];
    witnesses[0] = 0.3 - x[0];
    witnesses[1] = 0.3 + x[0];
    return 2;
  }
};

const int series_order = impactlab::taylor_order(1e-12);

// One trajectory's series, as the scalar Taylor stepper computes it.
void BM_PendulumSeriesOfOneTrajectory(benchmark::State& state) {
  auto series = std::make_unique<impactlab::TaylorSeries<double, 3>>();
  const std::array<double, 3> x0 = {0.1, 0.2, 0.0};
  const ForcedPendulumSeriesRhs rhs;
  for (auto _ : state) {
    series->evaluate(x0.data(), 0.5, series_order, rhs, false);
    benchmark::ClobberMemory();
  }
  state.counters["per_trajectory"] = benchmark::Counter(
      1.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PendulumSeriesOfOneTrajectory);

// The series of Arg lanes (1 to tape_lane_width) of different states, as a
// batch computes them: each lane's order 0 recorded on its tape, the
// higher orders in one pass over the lanes.
void BM_PendulumSeriesPassOverLanes(benchmark::State& state) {
  const int lanes = static_cast<int>(state.range(0));
  std::vector<std::unique_ptr<impactlab::SeriesTape>> tapes;
  std::array<const impactlab::SeriesTape*, impactlab::tape_lane_width> views{};
  for (int lane = 0; lane < lanes; ++lane) {
    tapes.push_back(std::make_unique<impactlab::SeriesTape>());
    views[lane] = tapes.back().get();
  }
  auto rows = std::make_unique<impactlab::SeriesLaneRows>();
  const ForcedPendulumSeriesRhs rhs;
  for (auto _ : state) {
    for (int lane = 0; lane < lanes; ++lane) {
      const std::array<double, 3> x0 = {0.1 + 0.01 * lane, 0.2, 0.0};
      impactlab::record_series_tape<3>(*tapes[lane], x0.data(), 0.5, rhs);
    }
    impactlab::replay_series_tapes(views, lanes, series_order, *rows);
    benchmark::ClobberMemory();
  }
  state.counters["per_trajectory"] = benchmark::Counter(
      static_cast<double>(lanes),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PendulumSeriesPassOverLanes)->Arg(1)->Arg(4)->Arg(8);

}  // namespace
