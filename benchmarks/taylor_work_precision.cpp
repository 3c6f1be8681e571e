// Work against precision of the Taylor stepper beside rkf78 on the jin2003
// periodic case (Model N, V0 = 1.5 m/s, θ(0) = 0, θ̇(0) = 0.1 rad/s), with
// impact-time errors measured against the extended-precision reference
// (the Taylor stepper in cpp_bin_float_quad at 1e-20,
// api/work_precision.hpp's extended_precision_reference) over 200
// forcing periods, and CPU time per impact (this thread, median of 5 runs of
// 2000 periods, event log counting only), steps and evaluations per impact.
// Side by side in one process, so a loaded machine slows both alike.
//
//   build/benchmarks/taylor_work_precision [repetitions [reference.txt]]
//
// reference.txt, if named: the reference impact times, one per line (%.17g),
// for errors of other tools (the SciPy loop) against the same reference.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <string_view>
#include <vector>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include "thread_cpu_time.hpp"

namespace {

using namespace impactlab;

struct Run {
  std::vector<double> impact_times;
  double cpu_seconds = 0.0;
  std::uint64_t steps = 0, rhs_evaluations = 0, impacts = 0;
};

template <class Stepper>
Run run(Stepper& stepper, const PendulumWalls& system, double t_end, double atol, bool keep) {
  EventLog log(keep);
  LoopOptions options;
  options.location.grazing_tolerance = atol;
  const double start = thread_cpu_seconds();
  const auto result = simulate(system, stepper, PendulumWalls::State{0.0, 0.1, 0.0},
                               PendulumMode::free, 0.0, t_end, options, log);
  Run out;
  out.cpu_seconds = thread_cpu_seconds() - start;
  out.steps = result.counters.steps;
  out.rhs_evaluations = result.counters.rhs_evaluations;
  out.impacts = log.count(EventKind::impact);
  for (const auto& e : log.records())
    if (e.kind == EventKind::impact) out.impact_times.push_back(e.t);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  PendulumWallsParameters p;
  p.V0 = 1.5;
  const PendulumWalls system(p);
  const double period = 2.0 * std::numbers::pi / p.omega;
  const double t_reference = 200.0 * period, t_timed = 2000.0 * period;

  StepperSettings quad_settings;
  quad_settings.rtol = quad_settings.atol = 1e-20;
  quad_settings.max_step = system.max_step();
  TaylorStepper<PendulumWalls, boost::multiprecision::cpp_bin_float_quad> quad(quad_settings);
  const Run reference = run(quad, system, t_reference, 1e-20, true);
  if (argc > 2) {
    if (std::FILE* file = std::fopen(argv[2], "w")) {
      for (const double t : reference.impact_times) std::fprintf(file, "%.17g\n", t);
      std::fclose(file);
    }
  }
  std::printf("reference: taylor in cpp_bin_float_quad at 1e-20 (order %d), %zu impacts, %.1f s CPU\n",
              quad.order(), reference.impact_times.size(), reference.cpu_seconds);
  std::printf("%-7s %7s %5s %10s %9s %14s %12s %11s\n", "method", "rtol", "order", "time_error",
              "us/impact", "impacts/s", "steps/impact", "rhs/impact");
  for (const std::string_view method : {"rkf78", "taylor"}) {
    for (const double rtol : {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13}) {
      StepperSettings settings;
      settings.rtol = rtol;
      settings.atol = 1e-2 * rtol;
      settings.max_step = system.max_step();
      const Run accuracy = with_stepper<PendulumWalls>(method, settings, [&](auto& stepper) {
        return run(stepper, system, t_reference, settings.atol, true);
      });
      double error = accuracy.impact_times.size() == reference.impact_times.size() ? 0.0 : INFINITY;
      for (std::size_t i = 0; i < std::min(accuracy.impact_times.size(), reference.impact_times.size()); ++i)
        error = std::max(error, std::fabs(accuracy.impact_times[i] - reference.impact_times[i]));
      std::vector<double> seconds;
      Run timed;
      for (int r = 0; r < repetitions; ++r) {
        timed = with_stepper<PendulumWalls>(method, settings, [&](auto& stepper) {
          return run(stepper, system, t_timed, settings.atol, false);
        });
        seconds.push_back(timed.cpu_seconds);
      }
      std::sort(seconds.begin(), seconds.end());
      const double per_impact = seconds[seconds.size() / 2] / static_cast<double>(timed.impacts);
      std::printf("%-7s %7.0e %5d %10.2e %9.2f %14.0f %12.1f %11.1f\n", std::string(method).c_str(),
                  rtol, method == "taylor" ? taylor_order(rtol) : 8, error, 1e6 * per_impact,
                  1.0 / per_impact, static_cast<double>(timed.steps) / timed.impacts,
                  static_cast<double>(timed.rhs_evaluations) / timed.impacts);
    }
  }
  return 0;
}
