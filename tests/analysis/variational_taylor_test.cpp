// The variational equations on the Taylor stepper (analysis/variational.hpp
// over a number type, integrate/dual_number.hpp), against independent
// computations:
// * the dual numbers' derivatives against the functions' derivatives in
//   closed form, along one direction and several (each direction as a
//   one-direction number seeded with it alone, bit for bit; a direction
//   known to be zero on a series skipped);
// * the pendulum's flow Jacobian (jin2003, Model N), in free flight and
//   across impacts, against rkf78 on the base system's Jacobian (the double
//   path, unchanged) and against central differences of the base flow;
// * the linear impact oscillator's flow Jacobian in free flight against its
//   closed form e^{Aτ}, and across impacts against the exact-flow stepper;
// * the largest Lyapunov exponent and the Floquet multipliers of the jin2003
//   periodic orbit with the Taylor stepper against rkf78.
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/dual_number.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/integrate/taylor_series.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

#include "support/base_flow.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::Dual;
using impactlab::FlowSetup;
using impactlab::LinearImpact;
using impactlab::PendulumWalls;
using impactlab::TangentMatrix;

static_assert(impactlab::HasSeriesRhs<impactlab::Variational<PendulumWalls>>);
static_assert(impactlab::HasSeriesRhs<impactlab::Variational<LinearImpact>>);
static_assert(impactlab::HasSeriesRhs<impactlab::Variational<impactlab::BouncingBall>>);

constexpr double two_pi = 2.0 * std::numbers::pi;

std::string fmt_number(double value) { return fmt::format("{}", value); }

// max |a − b| over the entries, and max |b|
double max_difference(const TangentMatrix& a, const TangentMatrix& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j) d = std::max(d, std::fabs(a[i][j] - b[i][j]));
  return d;
}
double max_entry(const TangentMatrix& a) {
  double m = 0.0;
  for (const auto& row : a)
    for (double v : row) m = std::max(m, std::fabs(v));
  return m;
}

// --- the dual numbers ---

TEST(DualNumber, DerivativesOfTheElementaryFunctions) {
  // f(x) along x = 0.3 + ε: the derivative part is f'(0.3)
  const double x = 0.3;
  const Dual<double> u(x, 1.0);
  EXPECT_DOUBLE_EQ((u * u).derivative(), 2.0 * x);
  EXPECT_DOUBLE_EQ((1.0 / u).derivative(), -1.0 / (x * x));
  EXPECT_DOUBLE_EQ((u / (u + 2.0)).derivative(), 2.0 / ((x + 2.0) * (x + 2.0)));
  EXPECT_DOUBLE_EQ((3.0 - 2.0 * u).derivative(), -2.0);
  EXPECT_DOUBLE_EQ((-u / 4.0).derivative(), -0.25);
  EXPECT_DOUBLE_EQ(sin(u).derivative(), std::cos(x));
  EXPECT_DOUBLE_EQ(cos(u).derivative(), -std::sin(x));
  EXPECT_DOUBLE_EQ(sin_angle(u).derivative(), std::cos(x));
  EXPECT_DOUBLE_EQ(sin_angle(u).value(), impactlab::sin_angle(x));
  // a phase far from zero: cos_phase's own argument reduction for the value
  const Dual<double> phase(1000.0, 2.0);
  EXPECT_DOUBLE_EQ(cos_phase(phase).value(), impactlab::cos_phase(1000.0));
  EXPECT_NEAR(cos_phase(phase).derivative(), -2.0 * std::sin(1000.0), 1e-15);
  EXPECT_EQ(sign(-u).value(), -1.0);
  EXPECT_EQ(sign(-u).derivative(), 0.0);
  EXPECT_DOUBLE_EQ(fabs(-u).derivative(), 1.0);  // d|−x|/dx = 1 at x > 0
  Dual<double> w = u;
  w *= u;
  w += 1.0;
  w /= u;  // (x² + 1) / x, derivative 1 − 1/x²
  EXPECT_DOUBLE_EQ(w.derivative(), 1.0 - 1.0 / (x * x));
}

// f(x, y) = sin x cos y + x / y, over any number type
template <class Number>
Number sine_cosine_quotient(const Number& x, const Number& y) {
  return sin(x) * cos(y) + x / y;
}

TEST(DualNumber, TwoDirectionsGiveThePartialDerivatives) {
  // f at (0.7, 1.3) along x (direction 0) and y (direction 1):
  // ∂f/∂x = cos x cos y + 1/y, ∂f/∂y = −sin x sin y − x/y²
  const double x0 = 0.7, y0 = 1.3;
  const Dual<double, 2> x(x0, {1.0, 0.0});
  const Dual<double, 2> y(y0, {0.0, 1.0});
  const Dual<double, 2> f = sine_cosine_quotient(x, y);
  EXPECT_DOUBLE_EQ(f.value(), std::sin(x0) * std::cos(y0) + x0 / y0);
  EXPECT_DOUBLE_EQ(f.derivative(0), std::cos(x0) * std::cos(y0) + 1.0 / y0);
  EXPECT_DOUBLE_EQ(f.derivative(1), -std::sin(x0) * std::sin(y0) - x0 / (y0 * y0));
  // each direction by the operations of a one-direction number seeded with
  // it alone: the same results, bit for bit
  const Dual<double> along_x =
      sine_cosine_quotient(Dual<double>(x0, 1.0), Dual<double>(y0, 0.0));
  const Dual<double> along_y =
      sine_cosine_quotient(Dual<double>(x0, 0.0), Dual<double>(y0, 1.0));
  EXPECT_EQ(f.value(), along_x.value());
  EXPECT_EQ(f.derivative(0), along_x.derivative());
  EXPECT_EQ(f.derivative(1), along_y.derivative());
}

TEST(DualNumber, ThreeDirectionsThroughTheRightHandSideFunctions) {
  // g(x, y) = cos_phase(x y) |x − y| / (2 + sin_angle(y)) at (0.4, 0.9),
  // the functions of the pendulum's right-hand side, along x, y and the
  // combination 2 x − y: the third derivative is 2 ∂g/∂x − ∂g/∂y (to
  // round-off), and
  // ∂g/∂x = (−y sin(x y) |x − y| − cos(x y)) / (2 + sin y),
  // ∂g/∂y = (−x sin(x y) |x − y| + cos(x y)) / (2 + sin y)
  //         − cos(x y) |x − y| cos y / (2 + sin y)²   (x < y)
  const double x0 = 0.4, y0 = 0.9;
  const Dual<double, 3> x(x0, {1.0, 0.0, 2.0});
  const Dual<double, 3> y(y0, {0.0, 1.0, -1.0});
  const Dual<double, 3> g = cos_phase(x * y) * fabs(x - y) / (2.0 + sin_angle(y));
  const double c = std::cos(x0 * y0), s = std::sin(x0 * y0), gap = y0 - x0;
  const double denominator = 2.0 + std::sin(y0);
  const double along_x = (-y0 * s * gap - c) / denominator;
  const double along_y = (-x0 * s * gap + c) / denominator -
                         c * gap * std::cos(y0) / (denominator * denominator);
  EXPECT_NEAR(g.value(), c * gap / denominator, 1e-15);
  EXPECT_NEAR(g.derivative(0), along_x, 1e-15);
  EXPECT_NEAR(g.derivative(1), along_y, 1e-15);
  EXPECT_NEAR(g.derivative(2), 2.0 * along_x - along_y, 1e-15);
}

TEST(DualNumber, AZeroDirectionOnASeriesStaysTheConstantZero) {
  // order 0 of a series x = 0.7 with derivatives (1, the constant 0): the
  // second direction is skipped through the products, the quotient, sin and
  // cos and stays the constant zero; the first is
  // d/dx [sin x cos x / (x + 2)] = (cos 2x (x + 2) − sin x cos x) / (x + 2)²
  using Series = impactlab::TaylorVariable<double>;
  using Evaluation = impactlab::TaylorEvaluation<double>;
  const auto rows = std::make_unique<Evaluation::Rows>();
  Evaluation evaluation(*rows, 0, 0.0, false);
  evaluation.start_order(0);
  const auto variable = [&](double value) {
    double* row = evaluation.take_row();
    row[0] = value;
    return Series(&evaluation, row, value, Series::unbounded);
  };
  const double x0 = 0.7;
  const Dual<Series, 2> x(variable(x0), {variable(1.0), Series(0.0)});
  const Dual<Series, 2> f = sin(x) * cos(x) / (x + 2.0);
  EXPECT_TRUE(f.derivative(1).is_constant());
  EXPECT_EQ(f.derivative(1).constant(), 0.0);
  ASSERT_FALSE(f.derivative(0).is_constant());
  EXPECT_NEAR(f.value().value(), std::sin(x0) * std::cos(x0) / (x0 + 2.0), 1e-15);
  EXPECT_NEAR(f.derivative(0).value(),
              (std::cos(2.0 * x0) * (x0 + 2.0) - std::sin(x0) * std::cos(x0)) /
                  ((x0 + 2.0) * (x0 + 2.0)),
              1e-15);
}

// --- flows ---


// ∂x(t1)/∂x(t0) on (θ, θ̇) by central differences of the base flow, step δ
template <class System>
TangentMatrix central_difference(const System& system, const FlowSetup& setup,
                                 const typename System::State& x0, typename System::Mode mode,
                                 double t0, double t1, double delta) {
  TangentMatrix j{};
  for (std::size_t column = 0; column < 2; ++column) {
    auto plus = x0, minus = x0;
    plus[column] += delta;
    minus[column] -= delta;
    const auto xp = flow(system, setup, plus, mode, t0, t1);
    const auto xm = flow(system, setup, minus, mode, t0, t1);
    for (std::size_t row = 0; row < 2; ++row) j[row][column] = (xp[row] - xm[row]) / (2 * delta);
  }
  return j;
}

const FlowSetup taylor{"taylor", 1e-12, 1e-14};
const FlowSetup rkf78{"rkf78", 1e-12, 1e-14};
const FlowSetup rkf78_tight{"rkf78", 1e-13, 1e-15};  // for the differences of the base flow

// the jin2003 pendulum's attractor after 100 forcing periods from θ = 0,
// θ̇ = 0.1 rad/s (a symmetric period-2 orbit, one impact per wall per period)
struct Attractor {
  PendulumWalls::State x;
  PendulumWalls::Mode mode;
  double t;
};
Attractor jin2003_attractor(const PendulumWalls& system, double period) {
  impactlab::EventLog log(false);
  const auto run = impactlab::with_flow<PendulumWalls>(
      rkf78.method, impactlab::stepper_settings(system, rkf78), [&](auto& stepper) {
        return impactlab::simulate(system, stepper, PendulumWalls::State{0.0, 0.1, 0.0},
                                   PendulumWalls::Mode::free, 0.0, 100 * period,
                                   impactlab::loop_options(rkf78), log);
      });
  return {run.state, run.mode, run.t};
}

// The Taylor tangent against rkf78 on the base's Jacobian and against central
// differences. Tolerances:
// * taylor against rkf78, both at rtol 1e-12: each carries Φ with a local
//   error of about rtol per unit of |Φ| per step, a few hundred steps per
//   span; 1e-9 (|Φ| + 1) leaves room for that sum and the saltation
//   matrices' event times (located to about atol / rate);
// * against central differences with δ = 2e-6 of flows at rtol 1e-13: the
//   truncation error is δ² |∂³x/∂x0³| / 6, and across the impacts the
//   flow's third derivative is large (the differences over two periods of
//   the attractor fall as δ², from 1e-2 at δ = 1e-3 to 1e-6 at δ = 1e-5:
//   about 1e4 δ², 4e-8 here); the integration error of the two flows (about
//   1e-13 |x|, not exactly smooth in x0) divided by δ is about 5e-8.
//   1e-6 (|Φ| + 1) covers both with a margin, and is far below the size of
//   any error in the linearisation itself (a wrong column or sign would
//   differ by order |Φ|).
void expect_pendulum_jacobians_agree(const PendulumWalls& system, const PendulumWalls::State& x0,
                                     PendulumWalls::Mode mode, double t0, double t1,
                                     std::uint64_t min_impacts, std::uint64_t max_impacts) {
  const auto by_taylor = impactlab::flow_with_jacobian(system, taylor, x0, mode, t0, t1);
  const auto by_rkf78 = impactlab::flow_with_jacobian(system, rkf78, x0, mode, t0, t1);
  ASSERT_EQ(by_taylor.termination, impactlab::Termination::completed);
  ASSERT_EQ(by_rkf78.termination, impactlab::Termination::completed);
  EXPECT_GE(by_taylor.impacts, min_impacts);
  EXPECT_LE(by_taylor.impacts, max_impacts);
  EXPECT_EQ(by_taylor.impacts, by_rkf78.impacts);
  EXPECT_EQ(by_taylor.mode, PendulumWalls::Mode::free);
  const double size = max_entry(by_rkf78.jacobian);
  const double against_rkf78 = max_difference(by_taylor.jacobian, by_rkf78.jacobian);
  EXPECT_LT(against_rkf78, 1e-9 * (size + 1.0)) << "|Phi| = " << size;
  const TangentMatrix differences = central_difference(system, rkf78_tight, x0, mode, t0, t1, 2e-6);
  const double against_differences = max_difference(by_taylor.jacobian, differences);
  EXPECT_LT(against_differences, 1e-6 * (size + 1.0)) << "|Phi| = " << size;
  // the base part is the base flow's
  for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(by_taylor.state[i], by_rkf78.state[i], 1e-10);
  ::testing::Test::RecordProperty("jacobian_size", fmt_number(size));
  ::testing::Test::RecordProperty("taylor_minus_rkf78", fmt_number(against_rkf78));
  ::testing::Test::RecordProperty("taylor_minus_central_difference", fmt_number(against_differences));
}

TEST(VariationalTaylor, PendulumFlowJacobianInFreeFlight) {
  // jin2003 from θ = 0, θ̇ = 0.1 rad/s: θ stays below 0.04 rad < θ0 ≈ 0.0715
  // rad for 0.4 s, no impact
  const impactlab::PendulumWallsParameters p;
  const PendulumWalls system(p);
  expect_pendulum_jacobians_agree(system, {0.0, 0.1, 0.0}, PendulumWalls::Mode::free, 0.0, 0.4, 0,
                                  0);
}

TEST(VariationalTaylor, PendulumFlowJacobianAcrossImpacts) {
  // two forcing periods on the jin2003 attractor (the period-2 orbit): an
  // impact on each wall
  const impactlab::PendulumWallsParameters p;
  const PendulumWalls system(p);
  const double period = two_pi / p.omega;
  const Attractor a = jin2003_attractor(system, period);
  ASSERT_EQ(a.mode, PendulumWalls::Mode::free);
  expect_pendulum_jacobians_agree(system, a.x, a.mode, a.t, a.t + 2 * period, 2, 2);
}

TEST(VariationalTaylor, PendulumContactPhasesCollapseTheJacobian) {
  // jin2003 at V0 = 4.163 m/s chatters into contact phases on the walls
  // (tests/contact/accumulation_test.cpp): the contact modes' series (the largest
  // right-hand sides of the tangent) are run, and an accumulation merges
  // nearby states, so the
  // Jacobian is zero after it, as rkf78's on the base's Jacobian is
  impactlab::PendulumWallsParameters p;
  p.V0 = 4.163;
  const PendulumWalls system(p);
  const double period = two_pi / p.omega;
  const PendulumWalls::State x0{0.0, 0.1, 0.0};
  impactlab::EventLog log(false);
  impactlab::with_flow<PendulumWalls>(
      rkf78.method, impactlab::stepper_settings(system, rkf78), [&](auto& stepper) {
        return impactlab::simulate(system, stepper, x0, PendulumWalls::Mode::free, 0.0, 3 * period,
                                   impactlab::loop_options(rkf78), log);
      });
  ASSERT_GE(log.count(impactlab::EventKind::contact_start), 1u);
  const auto by_taylor =
      impactlab::flow_with_jacobian(system, taylor, x0, PendulumWalls::Mode::free, 0.0, 3 * period);
  const auto by_rkf78 =
      impactlab::flow_with_jacobian(system, rkf78, x0, PendulumWalls::Mode::free, 0.0, 3 * period);
  ASSERT_EQ(by_taylor.termination, impactlab::Termination::completed);
  EXPECT_EQ(by_taylor.mode, by_rkf78.mode);
  EXPECT_EQ(by_taylor.impacts, by_rkf78.impacts);
  for (const auto& row : by_taylor.jacobian)
    for (double v : row) EXPECT_EQ(v, 0.0);
  for (const auto& row : by_rkf78.jacobian)
    for (double v : row) EXPECT_EQ(v, 0.0);
}

// e^{Aτ} of the damped oscillator ẍ + 2ζẋ + x = f(t), A = [[0, 1], [−1, −2ζ]]
// (ζ < 1, ω_d = √(1 − ζ²)):
// e^{−ζτ} [[c + ζ s / ω_d, s / ω_d], [−s / ω_d, c − ζ s / ω_d]], c = cos ω_d τ, s = sin ω_d τ
TangentMatrix damped_oscillator_transition(double zeta, double tau) {
  const double wd = std::sqrt(1.0 - zeta * zeta);
  const double decay = std::exp(-zeta * tau);
  const double c = std::cos(wd * tau), s = std::sin(wd * tau);
  return {{{decay * (c + zeta * s / wd), decay * s / wd},
           {-decay * s / wd, decay * (c - zeta * s / wd)}}};
}

TEST(VariationalTaylor, LinearOscillatorFlowJacobianIsTheClosedForm) {
  // free flight from x = 0 moving away from the stop at ẋ = −1: it stays
  // below σ = 0.2 for τ = 2.5 (A = 1, ω = 2; asserted: no impact); the
  // tangent equations are the linear system itself, so
  // Φ(τ) = e^{Aτ} whatever the state. The Taylor series of a linear system
  // is exact up to its order's truncation, controlled at rtol: 1e-11
  // (|Φ| <= 1) allows the steps' errors to add up
  const impactlab::LinearImpactParameters p;
  const LinearImpact system(p);
  const auto flow = impactlab::flow_with_jacobian(system, taylor, LinearImpact::State{0.0, -1.0},
                                                  LinearImpact::Mode::free, 0.0, 2.5);
  ASSERT_EQ(flow.termination, impactlab::Termination::completed);
  ASSERT_EQ(flow.impacts, 0u);
  const TangentMatrix expected = damped_oscillator_transition(p.zeta, 2.5);
  const double difference = max_difference(flow.jacobian, expected);
  EXPECT_LT(difference, 1e-11);
  RecordProperty("taylor_minus_closed_form", fmt_number(difference));
}

TEST(VariationalTaylor, LinearOscillatorFlowJacobianAcrossImpactsMatchesTheExactFlow) {
  // five forcing periods from rest at x = 0: impacts on the stop (defaults:
  // a period-1 orbit with one impact per period is reached), the exact
  // stepper's Jacobian from differences of closed-form flows
  const impactlab::LinearImpactParameters p;
  const LinearImpact system(p);
  const double period = two_pi / p.omega;
  const FlowSetup exact{"exact", 1e-12, 1e-13};
  const LinearImpact::State x0{0.0, 0.0};
  const auto by_taylor = impactlab::flow_with_jacobian(system, taylor, x0, LinearImpact::Mode::free,
                                                       0.0, 5 * period);
  const auto by_exact = impactlab::flow_with_jacobian(system, exact, x0, LinearImpact::Mode::free,
                                                      0.0, 5 * period);
  ASSERT_EQ(by_taylor.termination, impactlab::Termination::completed);
  ASSERT_EQ(by_exact.termination, impactlab::Termination::completed);
  ASSERT_GE(by_exact.impacts, 3u);
  EXPECT_EQ(by_taylor.impacts, by_exact.impacts);
  EXPECT_EQ(by_taylor.mode, by_exact.mode);
  // the same error budget as the pendulum's taylor against rkf78
  const double size = max_entry(by_exact.jacobian);
  const double difference = max_difference(by_taylor.jacobian, by_exact.jacobian);
  EXPECT_LT(difference, 1e-9 * (size + 1.0)) << "|Phi| = " << size;
  RecordProperty("jacobian_size", fmt_number(size));
  RecordProperty("taylor_minus_exact", fmt_number(difference));
}

TEST(VariationalTaylor, LyapunovExponentAndFloquetMultipliersOfTheJin2003Orbit) {
  // the jin2003 periodic orbit (V0 = 1.5 m/s, ω = 7 rad/s): the exponent over
  // 50 periods after 10 of alignment, on the same trajectory and tangent
  // vectors with either stepper, so they differ only by the periods'
  // Jacobians' errors (about 1e-9 relative, above), which change log |Φ v|
  // by as much per period: 1e-8 per second over 50 periods of 0.9 s
  const impactlab::PendulumWallsParameters p;
  const PendulumWalls system(p);
  const double period = two_pi / p.omega;
  const Attractor a = jin2003_attractor(system, period);
  const auto by_taylor =
      impactlab::largest_lyapunov_exponent(system, taylor, a.x, a.mode, a.t, period, 50, 10);
  const auto by_rkf78 =
      impactlab::largest_lyapunov_exponent(system, rkf78, a.x, a.mode, a.t, period, 50, 10);
  ASSERT_EQ(by_taylor.termination, impactlab::Termination::completed);
  ASSERT_EQ(by_rkf78.termination, impactlab::Termination::completed);
  EXPECT_LT(by_rkf78.exponent, 0.0);  // a stable orbit
  EXPECT_NEAR(by_taylor.exponent, by_rkf78.exponent, 1e-8);
  RecordProperty("lyapunov_rkf78", fmt_number(by_rkf78.exponent));
  RecordProperty("lyapunov_taylor_minus_rkf78", fmt_number(by_taylor.exponent - by_rkf78.exponent));

  // Floquet: Newton shooting on the period-2 map with the Taylor stepper
  const auto orbit_taylor = impactlab::locate_periodic_orbit(system, taylor, a.x, a.mode, a.t,
                                                             2 * period);
  const auto orbit_rkf78 = impactlab::locate_periodic_orbit(system, rkf78, a.x, a.mode, a.t,
                                                            2 * period);
  ASSERT_TRUE(orbit_taylor.converged);
  ASSERT_TRUE(orbit_rkf78.converged);
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_LT(std::abs(orbit_taylor.multipliers[i] - orbit_rkf78.multipliers[i]), 1e-8)
        << "multiplier " << i;
  RecordProperty("multiplier_taylor_minus_rkf78",
                 fmt_number(std::abs(orbit_taylor.multipliers[0] - orbit_rkf78.multipliers[0])));
}

}  // namespace
