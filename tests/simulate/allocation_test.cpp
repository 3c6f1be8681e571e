// The event loop allocates nothing: with the stepper built and the event log
// only counting, a run of many impacts (and contact phases) makes no heap
// allocation. Every allocation in this test program is counted
// (support/allocation_counter.hpp). One exception, outside this project's
// code: Boost.Odeint 1.74's bulirsch_stoer_dense_out::try_step builds two
// small std::vector work arrays per attempted step; for that stepper the test
// bounds the count by those.
#include <numbers>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

#include <impactlab/simulate/series_batch.hpp>

#include "support/allocation_counter.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

// Allocations made by simulate() alone, for the named stepper.
struct RunCount {
  long allocations = 0;
  std::uint64_t impacts = 0;
  std::uint64_t steps = 0;
};

template <class System>
RunCount count_run(const System& system, typename System::State x0, std::string_view method,
                   double t_end) {
  StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = system.max_step();
  EventLog log(false);
  LoopOptions options;
  return with_flow<System>(method, settings, [&](auto& stepper) {
    const long before = impactlab::testing::allocations_so_far();
    const auto result =
        simulate(system, stepper, x0, typename System::Mode{}, 0.0, t_end, options, log);
    const long made = impactlab::testing::allocations_so_far() - before;
    return RunCount{made, log.count(EventKind::impact), result.counters.steps};
  });
}

// no allocation, or for Bulirsch–Stoer at most Boost's two per step
void expect_no_allocation_of_ours(const RunCount& run, std::string_view method) {
  if (method == "bulirsch_stoer")
    EXPECT_LE(run.allocations, static_cast<long>(2 * run.steps + 2 * run.impacts));
  else
    EXPECT_EQ(run.allocations, 0);
}

class HotLoop : public ::testing::TestWithParam<std::string_view> {};

TEST_P(HotLoop, PendulumWithChatteringAndContactAllocatesNothing) {
  if (GetParam() == "exact") GTEST_SKIP() << "the pendulum has no closed-form flow";
  PendulumWallsParameters p;
  p.V0 = 4.163;
  const RunCount run =
      count_run(PendulumWalls(p), {0.0, 0.1, 0.0}, GetParam(), 100 * 2 * std::numbers::pi / p.omega);
  EXPECT_GT(run.impacts, 100u);
  expect_no_allocation_of_ours(run, GetParam());
}

TEST_P(HotLoop, LinearImpactAllocatesNothing) {
  const RunCount run = count_run(LinearImpact(LinearImpactParameters{}), {0.0, 0.0}, GetParam(), 300.0);
  EXPECT_GT(run.impacts, 20u);
  expect_no_allocation_of_ours(run, GetParam());
}

TEST_P(HotLoop, BouncingBallWithStickingAllocatesNothing) {
  const RunCount run = count_run(BouncingBall(BouncingBallParameters{}), {0.05, 0.0}, GetParam(), 5.0);
  EXPECT_GT(run.impacts, 20u);
  expect_no_allocation_of_ours(run, GetParam());
}

// The batch loop allocates nothing either: lanes of the pendulum (one
// system, so that its lanes' series are evaluated in passes over lanes, and
// several, evaluated side by side) chattering into contact, each lane's
// stepper built before it steps. The allocations are counted over each
// lane's run (the other lanes step in between: the sum counts them all).
TEST(HotLoop, BatchLanesAllocateNothingWhileStepping) {
  std::vector<PendulumWalls> systems;
  for (int i = 0; i < 6; ++i) {
    PendulumWallsParameters p;
    p.V0 = i < 4 ? 4.163 : 3.9 + 0.1 * i;
    systems.emplace_back(p);
  }
  long allocations = 0;
  std::uint64_t impacts = 0;
  std::size_t next = 0;
  const BatchStatistics statistics = run_in_lanes(4, [&](SeriesLane& lane) {
    if (next == systems.size()) return false;
    const PendulumWalls& system = systems[next];
    const PendulumWalls::State x0{-0.01 * static_cast<double>(next++), 0.1, 0.0};
    StepperSettings settings;
    settings.rtol = 1e-10;
    settings.atol = 1e-12;
    settings.max_step = system.max_step();
    settings.series_lane = &lane;
    EventLog log(false);
    LoopOptions options;
    TaylorStepper<PendulumWalls> stepper(settings);
    const long before = impactlab::testing::allocations_so_far();
    simulate(system, stepper, x0, PendulumWalls::Mode::free, 0.0,
             50 * 2 * std::numbers::pi / system.parameters().omega, options, log);
    allocations += impactlab::testing::allocations_so_far() - before;
    impacts += log.count(EventKind::impact);
    return true;
  });
  EXPECT_GT(impacts, 300u);
  EXPECT_GT(statistics.lane_series, 2 * statistics.evaluations);
  EXPECT_EQ(allocations, 0);
}

INSTANTIATE_TEST_SUITE_P(Steppers, HotLoop,
                         ::testing::ValuesIn(stepper_names),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
