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

#include "analysis/floquet.hpp"
#include "analysis/sweep.hpp"
#include "api/scene_jobs.hpp"
#include "api/scene_loading.hpp"
#include "io/scene.hpp"
#include "oscillators/bouncing_ball/bouncing_ball.hpp"
#include "oscillators/linear_impact/linear_impact.hpp"
#include "oscillators/pendulum_walls/pendulum_walls.hpp"

namespace {

using Complex = std::complex<double>;
using impactlab::FlowSetup;
using impactlab::LinearImpact;
using impactlab::LinearImpactParameters;

constexpr double two_pi = 2.0 * std::numbers::pi;

// all the digits, for the test report's properties
std::string fmt_number(double value) { return fmt::format("{}", value); }

double root_by_toms748(auto&& f, double a, double b) {
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      f, a, b, boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// The period-1 orbit with one impact per period of ẍ + 2ζẋ + x = A cos ωt,
// stop at σ, ẋ⁺ = −r ẋ⁻, in closed form.
struct ClosedFormOrbit {
  double impact_time;  // t* in [0, T)
  double velocity;     // ẋ⁻ > 0 at the impact
  std::array<Complex, 2> multipliers;
  double trace, determinant;  // of the monodromy matrix
};

class LinearImpactClosedForm {
 public:
  explicit LinearImpactClosedForm(const LinearImpactParameters& p)
      : p_(p),
        period_(two_pi / p.omega),
        amplitude_(p.A / Complex(1.0 - p.omega * p.omega, 2.0 * p.zeta * p.omega)) {
    // transition matrix of u'' + 2ζu' + u = 0 over one forcing period
    const double wd = std::sqrt(1.0 - p.zeta * p.zeta);
    const double decay = std::exp(-p.zeta * period_);
    const double c = std::cos(wd * period_), s = std::sin(wd * period_);
    phi_ = {{{decay * (c + p.zeta / wd * s), decay * s / wd},
             {-decay * s / wd, decay * (c - p.zeta / wd * s)}}};
  }

  [[nodiscard]] double particular_x(double t) const {
    return (amplitude_ * std::exp(Complex(0.0, p_.omega * t))).real();
  }
  [[nodiscard]] double particular_v(double t) const {
    return (Complex(0.0, p_.omega) * amplitude_ * std::exp(Complex(0.0, p_.omega * t))).real();
  }

  // ẋ⁻ that closes the position equation for an impact at t; F(t) closes the velocity one
  [[nodiscard]] double velocity_for(double t) const {
    const double a = p_.sigma - particular_x(t), vp = particular_v(t);
    return ((phi_[0][0] - 1.0) * a - phi_[0][1] * vp) / (p_.r * phi_[0][1]);
  }
  [[nodiscard]] double velocity_residual(double t) const {
    const double a = p_.sigma - particular_x(t), vp = particular_v(t);
    const double v = velocity_for(t);
    return phi_[1][0] * a + phi_[1][1] * (-p_.r * v - vp) - (v - vp);
  }

  // position between impacts, from just after the impact at t*
  [[nodiscard]] std::pair<double, double> state_after(double t_star, double v, double tau) const {
    const double wd = std::sqrt(1.0 - p_.zeta * p_.zeta);
    const double u0 = p_.sigma - particular_x(t_star);
    const double du0 = -p_.r * v - particular_v(t_star);
    const double decay = std::exp(-p_.zeta * tau);
    const double c = std::cos(wd * tau), s = std::sin(wd * tau);
    const double u = decay * ((c + p_.zeta / wd * s) * u0 + s / wd * du0);
    const double du = decay * (-s / wd * u0 + (c - p_.zeta / wd * s) * du0);
    return {u + particular_x(t_star + tau), du + particular_v(t_star + tau)};
  }

  // the admissible orbit: ẋ⁻ > 0 and x < σ strictly between impacts
  [[nodiscard]] std::optional<ClosedFormOrbit> orbit() const {
    const int grid = 2000;
    for (int k = 0; k < grid; ++k) {
      const double a = period_ * k / grid, b = period_ * (k + 1) / grid;
      const double fa = velocity_residual(a), fb = velocity_residual(b);
      if (!(fa * fb < 0.0)) continue;
      const double t = root_by_toms748([&](double x) { return velocity_residual(x); }, a, b);
      const double v = velocity_for(t);
      if (!(v > 0.0)) continue;
      bool admissible = true;
      for (int j = 1; j < 400 && admissible; ++j)
        admissible = state_after(t, v, period_ * j / 400).first < p_.sigma;
      if (!admissible) continue;
      ClosedFormOrbit orbit{t, v, {}, 0.0, 0.0};
      // S = [[−r, 0], [(1 + r)(A cos ωt* − σ)/v, −r]], monodromy S Φ
      const double s21 = (1.0 + p_.r) * (p_.A * std::cos(p_.omega * t) - p_.sigma) / v;
      const double m11 = -p_.r * phi_[0][0], m12 = -p_.r * phi_[0][1];
      const double m21 = s21 * phi_[0][0] - p_.r * phi_[1][0];
      const double m22 = s21 * phi_[0][1] - p_.r * phi_[1][1];
      orbit.trace = m11 + m22;
      orbit.determinant = m11 * m22 - m12 * m21;
      const Complex root = std::sqrt(Complex(orbit.trace * orbit.trace / 4.0 - orbit.determinant));
      orbit.multipliers = {orbit.trace / 2.0 + root, orbit.trace / 2.0 - root};
      if (std::abs(orbit.multipliers[1]) > std::abs(orbit.multipliers[0]))
        std::swap(orbit.multipliers[0], orbit.multipliers[1]);
      return orbit;
    }
    return std::nullopt;
  }

  [[nodiscard]] double period() const { return period_; }

 private:
  LinearImpactParameters p_;
  double period_;
  Complex amplitude_;
  std::array<std::array<double, 2>, 2> phi_;
};

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
  const auto transient = impactlab::with_stepper<impactlab::PendulumWalls>(
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
