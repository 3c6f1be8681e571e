// Cost per event of writing events.csv (io/output.hpp, EventsCsvWriter),
// against the cost of simulating that event: the jin2003 scene with its own
// integrator (rkf78, rtol 1e-12, atol 1e-14) over 200 forcing periods, events
// counted and not kept, in the same run of this program.
//   write_event_row   one impact row, all 14 columns (the Model N fields
//                     present, the others empty), into a temporary file
//   simulate_events   the run; time per event = time / events
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <numbers>

#include <impactlab/core/event_log.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/io/output.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace {

using namespace impactlab;

void write_event_row(benchmark::State& state) {
  const auto path = std::filesystem::temp_directory_path() / "impactlab_bench_events.csv";
  AtomicFile file(path);
  EventsCsvWriter writer(file);
  EventRecord impact{1234.5678901234567, EventKind::impact, 1, 0.071428571428571425,
                     -0.83912345678901234, 0.25173703703670370};
  impact.normal_impulse = 0.018234567890123456;
  impact.tangential_velocity = -1.2345678901234567;
  for (auto _ : state) {
    impact.t += 1e-3;
    writer.write(impact);
  }
  state.counters["events_per_second"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(write_event_row);

void simulate_events(benchmark::State& state) {
  PendulumWallsParameters parameters;
  parameters.V0 = 1.5;
  const PendulumWalls system(parameters);
  StepperSettings settings;
  settings.rtol = 1e-12;
  settings.atol = 1e-14;
  settings.max_step = system.max_step();
  LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  const double t_end = 200.0 * 2.0 * std::numbers::pi / parameters.omega;
  std::uint64_t events = 0;
  for (auto _ : state) {
    EventLog log(false);
    with_stepper<PendulumWalls>("rkf78", settings, [&](auto& stepper) {
      const auto run = simulate(system, stepper, PendulumWalls::State{0.0, 0.1, 0.0},
                                PendulumWalls::Mode::free, 0.0, t_end, options, log);
      benchmark::DoNotOptimize(run.t);
    });
    events += log.total();
  }
  state.counters["events_per_second"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
}
BENCHMARK(simulate_events)->Unit(benchmark::kMillisecond);

}  // namespace
