// The rigid pendulum's hot loop allocates nothing: fixed-size Eigen matrices
// in the impulse and contact problems, closed forms in the right-hand side
// and the witnesses. Every allocation of this test program is counted
// (support/allocation_counter.hpp, as in tests/simulate/allocation_test.cpp
// for the other oscillators).
#include <numbers>

#include <gtest/gtest.h>

#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/odeint_dopri5.hpp>
#include <impactlab/integrate/gsl_rk8pd.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

#include "support/allocation_counter.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

template <class Stepper>
void expect_no_allocation(bool spin_free, double V0) {
  RigidPendulumParameters p;
  p.pendulum.V0 = V0;
  p.radius = 0.01;
  p.spin_free = spin_free;
  const RigidPendulumWalls system(p);
  StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = system.max_step();
  Stepper stepper(settings);
  EventLog log(false);
  const long before = testing::allocations_so_far();
  simulate(system, stepper, RigidPendulumWalls::State{0.0, 0.1, 0.0, 0.0, 0.0},
           RigidPendulumWalls::Mode::free, 0.0, 100 * 2 * std::numbers::pi / p.pendulum.omega,
           LoopOptions{}, log);
  EXPECT_EQ(testing::allocations_so_far() - before, 0);
  EXPECT_GT(log.count(EventKind::impact), 90u);
}

TEST(RigidPendulumHotLoop, SpinFreeWithStickingImpactsAllocatesNothing) {
  expect_no_allocation<OdeintDopri5<RigidPendulumWalls::State>>(true, 1.5);
}

TEST(RigidPendulumHotLoop, SpinFreeWithContactPhasesAllocatesNothing) {
  expect_no_allocation<GslRk8pd<RigidPendulumWalls::State>>(true, 4.163);
}

TEST(RigidPendulumHotLoop, SpinLockedAllocatesNothing) {
  expect_no_allocation<OdeintDopri5<RigidPendulumWalls::State>>(false, 4.163);
}

}  // namespace
}  // namespace impactlab
