// Floquet multipliers, the period doubling they predict, and the Lyapunov
// exponent, against independent computations:
// * the period-1 one-impact orbit of the linear impact oscillator in closed
//   form (derived here: the damped oscillator's transition matrix over one
//   forcing period, the particular solution as a complex amplitude, the
//   impact phase solved by TOMS 748) and its multipliers from the textbook
//   saltation matrix of a Newton impact on a fixed stop;
// * the period doubling where a multiplier of that closed form passes −1,
//   against the one where the toolkit's Newton-shooting multipliers pass −1,
//   and against the brute-force sweep's change from period 1 to period 2;
// * the largest Lyapunov exponent of a stable periodic orbit against
//   log |largest Floquet multiplier| / period, to 1e-6.
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <boost/math/tools/roots.hpp>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/sweep.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

#include "support/linear_impact_closed_form.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using Complex = std::complex<double>;
using impactlab::FlowSetup;
using impactlab::LinearImpact;
using impactlab::LinearImpactParameters;
using impactlab::testing::ClosedFormOrbit;
using impactlab::testing::LinearImpactClosedForm;
using impactlab::testing::root_by_toms748;

constexpr double two_pi = 2.0 * std::numbers::pi;

// all the digits, for the test report's properties
std::string fmt_number(double value) { return fmt::format("{}", value); }

LinearImpactParameters parameters_at(double omega) {
  LinearImpactParameters p;  // ζ = 0.05, A = 1, σ = 0.2, r = 0.8
  p.omega = omega;
  return p;
}

// 1 + tr M + det M: zero where a multiplier is −1
double period_doubling_residual(double omega) {
  const auto orbit = LinearImpactClosedForm(parameters_at(omega)).orbit();
  EXPECT_TRUE(orbit.has_value()) << "no period-1 orbit at omega = " << omega;
  return orbit ? 1.0 + orbit->trace + orbit->determinant : NAN;
}

double closed_form_period_doubling() {
  return root_by_toms748([](double w) { return period_doubling_residual(w); }, 2.24, 2.29);
}

const FlowSetup exact_flow{"exact", 1e-12, 1e-13};

// The toolkit's period-1 orbit on the section t = 0 (mod T), from the closed
// form's state there as the guess.
auto toolkit_orbit(double omega) {
  const LinearImpactParameters p = parameters_at(omega);
  const LinearImpactClosedForm closed(p);
  const auto orbit = closed.orbit();
  const auto [x, v] = closed.state_after(orbit->impact_time, orbit->velocity,
                                         closed.period() - orbit->impact_time);
  const LinearImpact system(p);
  return impactlab::locate_periodic_orbit(system, exact_flow, LinearImpact::State{x, v},
                                          LinearImpact::Mode::free, 0.0, closed.period());
}

TEST(Floquet, LinearImpactMultipliersMatchTheClosedForm) {
  for (double omega : {2.0, 2.2, 2.265, 2.4}) {
    const auto closed = LinearImpactClosedForm(parameters_at(omega)).orbit();
    ASSERT_TRUE(closed.has_value());
    const auto orbit = toolkit_orbit(omega);
    ASSERT_TRUE(orbit.converged) << omega;
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(orbit.multipliers[k].real(), closed->multipliers[k].real(), 1e-8) << omega;
      EXPECT_NEAR(std::fabs(orbit.multipliers[k].imag()), std::fabs(closed->multipliers[k].imag()),
                  1e-8)
          << omega;
    }
  }
}

TEST(Floquet, PeriodDoublingOfTheLinearImpactOscillator) {
  const double omega_closed = closed_form_period_doubling();

  // the toolkit's multipliers pass −1 where (λ₁ + 1)(λ₂ + 1) = 1 + tr M + det M
  // of its monodromy matrix changes sign
  auto toolkit_residual = [](double omega) {
    const auto orbit = toolkit_orbit(omega);
    EXPECT_TRUE(orbit.converged) << omega;
    const auto& m = orbit.monodromy;
    return 1.0 + (m[0][0] + m[1][1]) + (m[0][0] * m[1][1] - m[0][1] * m[1][0]);
  };
  const double omega_toolkit =
      root_by_toms748(toolkit_residual, omega_closed - 0.003, omega_closed + 0.003);
  EXPECT_NEAR(omega_toolkit, omega_closed, 1e-8);
  RecordProperty("omega_closed_form", fmt_number(omega_closed));
  RecordProperty("omega_toolkit_floquet_minus_closed", fmt_number(omega_toolkit - omega_closed));

  // the brute-force sweep: period 1 below, period 2 above, within a grid step.
  // Other attractors coexist here, so the sweep starts on the period-1 branch
  // (the closed form's state at t = 0 at the first value) and follows it.
  impactlab::Scene scene = impactlab::load_scene("linear_impact");
  impactlab::SweepPlan plan;
  const double step = 0.001;
  {
    const LinearImpactClosedForm closed(parameters_at(omega_closed - 9.5 * step));
    const auto orbit = closed.orbit();
    const auto [x, v] = closed.state_after(orbit->impact_time, orbit->velocity,
                                           closed.period() - orbit->impact_time);
    scene.values["initial.x"] = x;
    scene.values["initial.x_dot"] = v;
  }
  // a grid with no value on the bifurcation itself (the multiplier −1 there
  // makes the approach to the orbit algebraic, not geometric)
  plan.axes = {{"omega", omega_closed - 9.5 * step, omega_closed + 9.5 * step, 20}};
  plan.section.transient_periods = 1500;
  plan.section.points = 32;
  const impactlab::SweepTarget target = impactlab::sweep_target(scene);
  impactlab::validate_plan(plan, scene, *target.schema);
  const auto tasks = impactlab::sweep_tasks(plan);
  ASSERT_EQ(tasks.size(), 1u);
  const auto records = impactlab::run_sweep_task(
      scene, target, plan, tasks[0], [](int) { return nullptr; }, [](const auto&) {}, [] { return true; });
  ASSERT_EQ(records.size(), 20u);
  double last_period_one = -INFINITY, first_period_two = INFINITY;
  for (const auto& record : records) {
    const double omega = plan.axes[0].value(record.index[0]);
    const int period = record.classification.period;
    EXPECT_TRUE(period == 1 || period == 2) << omega << ": period " << period;
    if (period == 1) last_period_one = std::max(last_period_one, omega);
    if (period == 2) first_period_two = std::min(first_period_two, omega);
  }
  EXPECT_LT(last_period_one, first_period_two);
  EXPECT_LT(last_period_one, omega_closed);
  EXPECT_GT(first_period_two, omega_closed);
  EXPECT_LT(first_period_two - last_period_one, 1.5 * step);
  RecordProperty("sweep_last_period_one", fmt_number(last_period_one));
  RecordProperty("sweep_first_period_two", fmt_number(first_period_two));
}

TEST(Lyapunov, StablePeriodicOrbitOfTheLinearImpactOscillator) {
  // just below the period doubling the multipliers are real and distinct
  const double omega = closed_form_period_doubling() - 0.002;
  const auto closed = LinearImpactClosedForm(parameters_at(omega)).orbit();
  ASSERT_TRUE(closed.has_value());
  ASSERT_EQ(closed->multipliers[0].imag(), 0.0);
  ASSERT_LT(std::abs(closed->multipliers[0]), 1.0);
  const auto orbit = toolkit_orbit(omega);
  ASSERT_TRUE(orbit.converged);
  const double period = two_pi / omega;
  const double expected = std::log(std::abs(closed->multipliers[0])) / period;
  const LinearImpact system(parameters_at(omega));
  const auto lyapunov = impactlab::largest_lyapunov_exponent(
      system, exact_flow, orbit.state, orbit.mode, 0.0, period, 400, 60);
  EXPECT_NEAR(lyapunov.exponent, expected, 1e-6);
  RecordProperty("lyapunov_minus_closed_form", fmt_number(lyapunov.exponent - expected));
  EXPECT_NEAR(lyapunov.exponent, std::log(std::abs(orbit.multipliers[0])) / period, 1e-6);
}

TEST(Lyapunov, StablePeriodTwoOrbitOfThePendulum) {
  // jin2003 (V0 = 1.5 m/s, ω = 7 rad/s): a symmetric period-2 orbit, one
  // impact on each wall per forcing period
  impactlab::PendulumWallsParameters p;
  const impactlab::PendulumWalls system(p);
  const FlowSetup setup{"rk8pd", 1e-12, 1e-13};
  const double period = two_pi / p.omega;
  impactlab::EventLog log(false);
  const auto transient = impactlab::with_flow<impactlab::PendulumWalls>(
      setup.method, impactlab::stepper_settings(system, setup), [&](auto& stepper) {
        return impactlab::simulate(system, stepper, impactlab::PendulumWalls::State{0.0, 0.1, 0.0},
                                   impactlab::PendulumWalls::Mode::free, 0.0, 100 * period,
                                   impactlab::loop_options(setup), log);
      });
  const auto orbit = impactlab::locate_periodic_orbit(system, setup, transient.state,
                                                      transient.mode, 100 * period, 2 * period);
  ASSERT_TRUE(orbit.converged);
  ASSERT_LT(std::abs(orbit.multipliers[0]), 1.0);
  ASSERT_GT(std::abs(orbit.multipliers[0]), 2.0 * std::abs(orbit.multipliers[1]));
  const auto lyapunov = impactlab::largest_lyapunov_exponent(
      system, setup, orbit.state, orbit.mode, 100 * period, period, 200, 20);
  EXPECT_NEAR(lyapunov.exponent, std::log(std::abs(orbit.multipliers[0])) / (2 * period), 1e-6);
  RecordProperty("lyapunov_minus_floquet",
                 fmt_number(lyapunov.exponent -
                            std::log(std::abs(orbit.multipliers[0])) / (2 * period)));
}

TEST(Lyapunov, BallRestingOnTheTableMergesNearbyStates) {
  // Γ = Aω²/g ≈ 0.46 < 1: the table never throws the ball; a nearby ball
  // (lifted or thrown a little) falls back, chatters and rides again, so the
  // tangent map of the riding mode is zero and the exponent is −∞
  impactlab::BouncingBallParameters p;
  p.A = 0.005;
  const impactlab::BouncingBall system(p);
  const double period = two_pi / p.omega;
  const impactlab::BouncingBall::State riding{system.table_position(0.0),
                                              system.table_velocity(0.0)};
  const auto lyapunov = impactlab::largest_lyapunov_exponent(
      system, exact_flow, riding, impactlab::BouncingBall::Mode::stuck, 0.0, period, 20, 2);
  EXPECT_EQ(lyapunov.exponent, -INFINITY);
  // and a ball thrown up 1 mm above it lands, chatters and rides: the flow's
  // Jacobian over a few periods is zero as well
  const auto thrown = impactlab::flow_with_jacobian(
      system, exact_flow, {riding[0] + 1e-3, riding[1]}, impactlab::BouncingBall::Mode::free, 0.0,
      5 * period);
  EXPECT_EQ(thrown.mode, impactlab::BouncingBall::Mode::stuck);
  for (const auto& row : thrown.jacobian)
    for (double v : row) EXPECT_EQ(v, 0.0);
}

}  // namespace
