// The saltation-corrected Jacobian of the event-driven flow against an
// independent one: central finite differences of the full event-driven
// simulation (the base system, no variational equations), perturbing the
// initial state. Over one forcing period with impacts, for the linear impact
// oscillator (exact flow), the bouncing ball (exact flow, moving table: the
// reset and the witness depend on time explicitly) and the pendulum between
// two walls (Model N, an ODE stepper), and for the linear impact oscillator
// also against the closed-form saltation matrix of a Newton impact on a fixed
// stop.
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/saltation.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

#include "support/base_flow.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::FlowSetup;
using impactlab::TangentMatrix;

// ∂x(t1)/∂x(t0) on (q, q̇) by central differences with steps h_q, h_qdot.
template <class System>
TangentMatrix finite_difference_jacobian(const System& system, const FlowSetup& setup,
                                         const typename System::State& x0,
                                         typename System::Mode mode, double t0, double t1,
                                         std::array<double, 2> h) {
  TangentMatrix j{};
  for (int column = 0; column < 2; ++column) {
    auto plus = x0, minus = x0;
    plus[column] += h[column];
    minus[column] -= h[column];
    const auto xp = flow(system, setup, plus, mode, t0, t1);
    const auto xm = flow(system, setup, minus, mode, t0, t1);
    for (int row = 0; row < 2; ++row) j[row][column] = (xp[row] - xm[row]) / (2.0 * h[column]);
  }
  return j;
}

void expect_matrix_near(const TangentMatrix& actual, const TangentMatrix& expected,
                        double relative) {
  double scale = 0.0;
  for (const auto& row : expected)
    for (double v : row) scale = std::max(scale, std::fabs(v));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(actual[i][j], expected[i][j], relative * scale) << "entry " << i << j;
}

TEST(Saltation, LinearImpactOnePeriodMatchesFiniteDifferences) {
  impactlab::LinearImpactParameters p;  // the default period-1 impacting orbit, ω = 2
  const impactlab::LinearImpact system(p);
  const FlowSetup setup{"exact", 1e-12, 1e-13};
  const double period = 2.0 * std::numbers::pi / p.omega;
  // a state on the attractor, then one period with its impact
  const auto x0 = flow(system, setup, {0.0, 0.0}, impactlab::LinearImpact::Mode::free, 0.0,
                       100 * period);
  std::uint64_t impacts = 0;
  flow(system, setup, x0, impactlab::LinearImpact::Mode::free, 100 * period, 101 * period,
       &impacts);
  ASSERT_EQ(impacts, 1u);
  const auto tangent = impactlab::flow_with_jacobian(system, setup, x0,
                                                     impactlab::LinearImpact::Mode::free,
                                                     100 * period, 101 * period);
  const auto reference = finite_difference_jacobian(
      system, setup, x0, impactlab::LinearImpact::Mode::free, 100 * period, 101 * period,
      {1e-4, 1e-4});
  expect_matrix_near(tangent.jacobian, reference, 1e-6);
}

TEST(Saltation, LinearImpactClosedFormSaltationMatrix) {
  // S = [[−r, 0], [(1 + r)(A cos ωt − σ)/v, −r]] for x = σ, ẋ⁻ = v > 0
  // (Nordmark 1991; derived from S = G + (f⁺ − G f⁻) ∇hᵀ / ḣ by hand)
  impactlab::LinearImpactParameters p;
  const impactlab::LinearImpact system(p);
  const double t = 0.37, v = 1.3;
  const impactlab::LinearImpact::State x{p.sigma, v};
  impactlab::EventLog log(false);
  const auto after = system.on_event(impactlab::LinearImpact::Mode::free, 0,
                                     impactlab::CrossingKind::crossing, x, t, log);
  ASSERT_EQ(after.mode, impactlab::LinearImpact::Mode::free);
  const TangentMatrix s = impactlab::saltation_matrix(
      system, impactlab::LinearImpact::Mode::free, 0, impactlab::CrossingKind::crossing, x, t,
      after).matrix;
  const double push = p.A * std::cos(p.omega * t) - p.sigma;
  const TangentMatrix expected{{{-p.r, 0.0}, {(1.0 + p.r) * push / v, -p.r}}};
  expect_matrix_near(s, expected, 1e-14);
}

TEST(Saltation, BouncingBallMovingTableMatchesFiniteDifferences) {
  impactlab::BouncingBallParameters p;
  p.A = 0.01;  // Γ = Aω²/g ≈ 0.92: bounces without sticking, r = 0.8
  const impactlab::BouncingBall system(p);
  const FlowSetup setup{"exact", 1e-12, 1e-13};
  const double period = 2.0 * std::numbers::pi / p.omega;
  const impactlab::BouncingBall::State x0{0.02, 0.5};
  std::uint64_t impacts = 0;
  const auto x1 =
      flow(system, setup, x0, impactlab::BouncingBall::Mode::free, 0.0, 2 * period, &impacts);
  ASSERT_GE(impacts, 1u);
  ASSERT_GT(x1[0], system.table_position(2 * period));  // bouncing, not riding on the table
  const auto tangent = impactlab::flow_with_jacobian(
      system, setup, x0, impactlab::BouncingBall::Mode::free, 0.0, 2 * period);
  const auto reference = finite_difference_jacobian(
      system, setup, x0, impactlab::BouncingBall::Mode::free, 0.0, 2 * period, {1e-6, 1e-5});
  expect_matrix_near(tangent.jacobian, reference, 1e-6);
}

TEST(Saltation, PendulumModelNFreeFlightAndImpactsMatchFiniteDifferences) {
  impactlab::PendulumWallsParameters p;  // jin2003: V0 = 1.5 m/s, ω = 7 rad/s
  const impactlab::PendulumWalls system(p);
  const FlowSetup setup{"rk8pd", 1e-13, 1e-14};
  const double period = 2.0 * std::numbers::pi / p.omega;
  const auto x0 = flow(system, setup, {0.0, 0.1, 0.0}, impactlab::PendulumWalls::Mode::free, 0.0,
                       60 * period);
  std::uint64_t impacts = 0;
  flow(system, setup, x0, impactlab::PendulumWalls::Mode::free, 60 * period, 61 * period,
       &impacts);
  ASSERT_GE(impacts, 1u);
  const auto tangent = impactlab::flow_with_jacobian(
      system, setup, x0, impactlab::PendulumWalls::Mode::free, 60 * period, 61 * period);
  const auto reference = finite_difference_jacobian(
      system, setup, x0, impactlab::PendulumWalls::Mode::free, 60 * period, 61 * period,
      {1e-6, 1e-5});
  expect_matrix_near(tangent.jacobian, reference, 1e-5);
}

// A period with a contact phase: every nearby state chatters into contact
// and is released at the time the forcing sets (g + z̈ = 0), riding on the
// table, so the period map is locally constant. The tangent map is exactly
// zero (the saltation matrix of the accumulation is zero); the finite
// differences of the full simulation show the same.
TEST(Saltation, BouncingBallStickingPhaseCollapsesNearbyStates) {
  const impactlab::BouncingBallParameters p;  // the scene's Γ ≈ 1.03, r = 0.8: sticks each period
  const impactlab::BouncingBall system(p);
  const FlowSetup setup{"exact", 1e-12, 1e-13};
  const double period = 2.0 * std::numbers::pi / p.omega;
  // a start in flight: the first of the times 50T + kT/8 where the ball is free
  auto run_to = [&](double t_end, impactlab::EventLog& log) {
    return impactlab::with_flow<impactlab::BouncingBall>(
        setup.method, impactlab::stepper_settings(system, setup), [&](auto& stepper) {
          return impactlab::simulate(system, stepper, impactlab::BouncingBall::State{0.05, 0.0},
                                     impactlab::BouncingBall::Mode::free, 0.0, t_end,
                                     impactlab::loop_options(setup), log);
        });
  };
  double start = 0.0;
  impactlab::BouncingBall::State x0{};
  for (int k = 0; k < 8 && start == 0.0; ++k) {
    impactlab::EventLog ignored(false);
    const auto at = run_to(50 * period + k * period / 8, ignored);
    if (at.mode == impactlab::BouncingBall::Mode::free) {
      start = 50 * period + k * period / 8;
      x0 = at.state;
    }
  }
  ASSERT_GT(start, 0.0);
  impactlab::EventLog log(true);
  const auto run = impactlab::with_flow<impactlab::BouncingBall>(
      setup.method, impactlab::stepper_settings(system, setup), [&](auto& stepper) {
        return impactlab::simulate(system, stepper, x0, impactlab::BouncingBall::Mode::free, start,
                                   start + period, impactlab::loop_options(setup), log);
      });
  ASSERT_EQ(run.mode, impactlab::BouncingBall::Mode::free);
  ASSERT_EQ(log.count(impactlab::EventKind::contact_start), 1u);
  ASSERT_EQ(log.count(impactlab::EventKind::contact_end), 1u);
  const auto tangent = impactlab::flow_with_jacobian(
      system, setup, x0, impactlab::BouncingBall::Mode::free, start, start + period);
  const auto reference = finite_difference_jacobian(
      system, setup, x0, impactlab::BouncingBall::Mode::free, start, start + period,
      {1e-6, 1e-6});
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(tangent.jacobian[i][j], 0.0);
      EXPECT_LT(std::fabs(reference[i][j]), 1e-6) << "entry " << i << j;
    }
}

// The same for the pendulum (Model N) at V0 = 5 m/s, where the steady state
// chatters into a sliding contact on a wall and is released where g_e = 0.
TEST(Saltation, PendulumContactPhaseCollapsesNearbyStates) {
  impactlab::PendulumWallsParameters p;
  p.V0 = 5.0;
  const impactlab::PendulumWalls system(p);
  const FlowSetup setup{"rk8pd", 1e-12, 1e-13};
  const double period = 2.0 * std::numbers::pi / p.omega;
  using Pendulum = impactlab::PendulumWalls;
  auto run_from = [&](const Pendulum::State& x, Pendulum::Mode mode, double t0, double t1,
                      impactlab::EventLog& log) {
    return impactlab::with_flow<Pendulum>(
        setup.method, impactlab::stepper_settings(system, setup), [&](auto& stepper) {
          return impactlab::simulate(system, stepper, x, mode, t0, t1,
                                     impactlab::loop_options(setup), log);
        });
  };
  // a start in free flight after the transient: the first of 100T + kT/8
  double start = 0.0;
  Pendulum::State x0{};
  for (int k = 0; k < 16 && start == 0.0; ++k) {
    impactlab::EventLog ignored(false);
    const auto at = run_from({0.0, 0.1, 0.0}, Pendulum::Mode::free, 0.0,
                             100 * period + k * period / 8, ignored);
    if (at.mode == Pendulum::Mode::free && at.termination == impactlab::Termination::completed) {
      start = 100 * period + k * period / 8;
      x0 = at.state;
    }
  }
  ASSERT_GT(start, 0.0);
  const double end = start + 2 * period;  // the steady state has period 2
  impactlab::EventLog log(true);
  const auto run = run_from(x0, Pendulum::Mode::free, start, end, log);
  ASSERT_EQ(run.termination, impactlab::Termination::completed);
  ASSERT_GE(log.count(impactlab::EventKind::contact_start), 1u);
  ASSERT_GE(log.count(impactlab::EventKind::contact_end), 1u);
  ASSERT_EQ(run.mode, Pendulum::Mode::free);
  const auto tangent =
      impactlab::flow_with_jacobian(system, setup, x0, Pendulum::Mode::free, start, end);
  const auto reference = finite_difference_jacobian(system, setup, x0, Pendulum::Mode::free,
                                                    start, end, {1e-7, 1e-6});
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(tangent.jacobian[i][j], 0.0);
      EXPECT_LT(std::fabs(reference[i][j]), 1e-6) << "entry " << i << j;
    }
}

}  // namespace
