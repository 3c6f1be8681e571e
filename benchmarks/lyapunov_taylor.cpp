// CPU time of the largest Lyapunov exponent (analysis/floquet.hpp) on the
// jin2003 periodic case (Model N, V0 = 1.5 m/s, ω = 7 rad/s), with the
// variational equations integrated by rkf78 (the scene's integrator) and by
// the Taylor stepper: the point is the state after a transient of
// 100 forcing periods from θ = 0, θ̇ = 0.1 rad/s (rkf78 at 1e-12), the
// exponent averaged over `periods` periods after 10 of alignment. CPU time of
// this thread, the median of `repetitions` runs; the exponents with all
// their digits, so that two builds can be compared bit for bit.
//
//   build/benchmarks/lyapunov_taylor [periods [repetitions]]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <impactlab/analysis/floquet.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include "thread_cpu_time.hpp"

namespace {

using namespace impactlab;

}  // namespace

int main(int argc, char** argv) {
  const int periods = argc > 1 ? std::atoi(argv[1]) : 50;
  const int repetitions = argc > 2 ? std::atoi(argv[2]) : 5;
  const PendulumWallsParameters p;  // jin2003: V0 = 1.5 m/s, ω = 7 rad/s
  const PendulumWalls system(p);
  const double period = 2.0 * std::numbers::pi / p.omega;
  const int alignment_periods = 10;

  // the attractor: 100 periods of transient with the scene's integrator
  const FlowSetup transient_setup{"rkf78", 1e-12, 1e-14};
  EventLog log(false);
  const auto transient = with_stepper<PendulumWalls>(
      transient_setup.method, stepper_settings(system, transient_setup), [&](auto& stepper) {
        return simulate(system, stepper, PendulumWalls::State{0.0, 0.1, 0.0}, PendulumMode::free,
                        0.0, 100 * period, loop_options(transient_setup), log);
      });
  const double t0 = 100 * period;
  std::printf("# jin2003 V0 = %g m/s, omega = %g rad/s; %d periods after %d of alignment; "
              "median CPU of %d runs\n",
              p.V0, p.omega, periods, alignment_periods, repetitions);
  std::printf("%-15s %8s %8s %12s %26s\n", "method", "rtol", "atol", "cpu_ms", "exponent_per_s");

  const std::vector<FlowSetup> setups = {
      {"dopri5", 1e-10, 1e-12}, {"rk8pd", 1e-12, 1e-14},  {"bulirsch_stoer", 1e-12, 1e-14},
      {"rkf78", 1e-12, 1e-14},  {"taylor", 1e-12, 1e-14}, {"taylor", 1e-10, 1e-12}};
  for (const FlowSetup& setup : setups) {
    std::vector<double> times;
    double exponent = 0.0;
    try {
      for (int r = 0; r < repetitions; ++r) {
        const double start = thread_cpu_seconds();
        const LyapunovResult result = largest_lyapunov_exponent(
            system, setup, transient.state, transient.mode, t0, period, periods, alignment_periods);
        times.push_back(thread_cpu_seconds() - start);
        exponent = result.exponent;
      }
    } catch (const std::invalid_argument& e) {
      std::printf("%-15s %8.0e %8.0e %12s %26s\n", setup.method.c_str(), setup.rtol, setup.atol,
                  "n/a", e.what());
      continue;
    }
    std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
    std::printf("%-15s %8.0e %8.0e %12.3f %26.17g\n", setup.method.c_str(), setup.rtol, setup.atol,
                1e3 * times[times.size() / 2], exponent);
  }
  return 0;
}
