// Impacts per second of the pendulum between two walls (Jin, Hu & Bishop
// 2003; Model N), per stepper, at rtol = 1e-10, atol = 1e-12 (and the
// Taylor stepper beside rkf78 at rtol = 1e-12, atol = 1e-12, and alone at
// rtol = 1e-8, atol = 1e-12).
//
// Each iteration simulates a fixed 2000 forcing periods from θ(0) = 0,
// θ̇(0) = 0.1 rad/s with the paper's defaults and the event log counting only
// (keep_records = false), so the time is the event loop's: steps, event
// location, root refinement, resets. Cases:
//   periodic    V0 = 1.5 m/s,   ω = 7 rad/s: about one impact per period
//   chattering  V0 = 4.163 m/s, ω = 7 rad/s: chatter sequences, an
//               accumulation and a sustained-contact phase
// Counters: impacts_per_second (impacts / CPU second), rhs_per_impact and
// steps_per_impact (right-hand-side evaluations and accepted steps per impact).
// The flow_* cases run the same through Flow<PendulumWalls>
// (simulate/flow.hpp), the stepper chosen by name at run time as the scene
// API runs every analysis, beside the loop instantiated for the stepper
// directly: what the run-time choice costs.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <numbers>
#include <string_view>

#include <impactlab/core/event_log.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace {

using impactlab::EventKind;
using impactlab::EventLog;
using impactlab::LoopOptions;
using impactlab::PendulumWalls;
using impactlab::PendulumWallsParameters;
using impactlab::StepperSettings;

constexpr double forcing_periods = 2000.0;

enum class Dispatch { compiled, flow };

template <Dispatch dispatch>
void impacts_per_second_through(benchmark::State& state, std::string_view method, double V0,
                                double rtol) {
  PendulumWallsParameters parameters;
  parameters.V0 = V0;
  const PendulumWalls system(parameters);
  StepperSettings settings;
  settings.rtol = rtol;
  settings.atol = std::min(1e-12, rtol);
  settings.max_step = system.max_step();
  const double t_end = forcing_periods * 2.0 * std::numbers::pi / parameters.omega;  // s
  const PendulumWalls::State x0 = {0.0, 0.1, 0.0};

  std::uint64_t impacts = 0, rhs_evaluations = 0, steps = 0;
  for (auto _ : state) {
    EventLog log(false);
    const auto result = [&] {
      if constexpr (dispatch == Dispatch::flow)
        return impactlab::run_flow(system, method, settings, x0, PendulumWalls::Mode::free, 0.0,
                                   t_end, LoopOptions{}, log);
      else
        return impactlab::with_stepper<PendulumWalls>(method, settings, [&](auto& stepper) {
          return impactlab::simulate(system, stepper, x0, PendulumWalls::Mode::free, 0.0, t_end,
                                     LoopOptions{}, log);
        });
    }();
    benchmark::DoNotOptimize(result.state);
    if (result.termination != impactlab::Termination::completed) {
      state.SkipWithError("run did not complete");
      return;
    }
    impacts += log.count(EventKind::impact);
    rhs_evaluations += result.counters.rhs_evaluations;
    steps += result.counters.steps;
  }
  const double per_impact = impacts > 0 ? 1.0 / static_cast<double>(impacts) : 0.0;
  state.counters["impacts_per_second"] =
      benchmark::Counter(static_cast<double>(impacts), benchmark::Counter::kIsRate);
  state.counters["rhs_per_impact"] = static_cast<double>(rhs_evaluations) * per_impact;
  state.counters["steps_per_impact"] = static_cast<double>(steps) * per_impact;
}

void impacts_per_second(benchmark::State& state, std::string_view method, double V0,
                        double rtol = 1e-10) {
  impacts_per_second_through<Dispatch::compiled>(state, method, V0, rtol);
}

void flow_impacts_per_second(benchmark::State& state, std::string_view method, double V0,
                             double rtol = 1e-10) {
  impacts_per_second_through<Dispatch::flow>(state, method, V0, rtol);
}

BENCHMARK_CAPTURE(impacts_per_second, periodic_dopri5, "dopri5", 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, periodic_rkf78, "rkf78", 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, periodic_bulirsch_stoer, "bulirsch_stoer", 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, periodic_rk8pd, "rk8pd", 1.5)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, periodic_taylor, "taylor", 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, periodic_rkf78_rtol1e12, "rkf78", 1.5, 1e-12)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, periodic_taylor_rtol1e12, "taylor", 1.5, 1e-12)
    ->Unit(benchmark::kMillisecond);
// the rtol whose impact-time error is <= 1e-9 s (2.9e-10 s, docs/performance.md)
BENCHMARK_CAPTURE(impacts_per_second, periodic_taylor_rtol1e8, "taylor", 1.5, 1e-8)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, chattering_taylor, "taylor", 4.163)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, chattering_dopri5, "dopri5", 4.163)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, chattering_rkf78, "rkf78", 4.163)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, chattering_bulirsch_stoer, "bulirsch_stoer", 4.163)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(impacts_per_second, chattering_rk8pd, "rk8pd", 4.163)
    ->Unit(benchmark::kMillisecond);

}  // namespace
BENCHMARK_CAPTURE(flow_impacts_per_second, periodic_rkf78, "rkf78", 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(flow_impacts_per_second, periodic_taylor, "taylor", 1.5)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(flow_impacts_per_second, chattering_taylor, "taylor", 4.163)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(flow_impacts_per_second, chattering_rkf78, "rkf78", 4.163)
    ->Unit(benchmark::kMillisecond);
