// The Lyapunov spectrum (analysis/lyapunov_spectrum.hpp) against closed forms
// written here:
// * on a stable periodic orbit, λ_i = ln |μ_i| / T with μ_i its Floquet
//   multipliers: the linear impact oscillator's from the closed-form orbit
//   (tests/support/linear_impact_closed_form.hpp); the bouncing ball's from
//   the Jacobian of its impact map (t_k, ẏ_k⁺) ↦ (t_{k+1}, ẏ_{k+1}⁺) derived
//   here by implicit differentiation of the flight's landing condition; a
//   4-state model file (the linear impact oscillator beside an uncoupled,
//   overdamped oscillator with real multipliers e^{(−ζ₂ ± √(ζ₂² − 1)) T});
// * on chaotic orbits without contact phases, the sum of the exponents is the
//   phase-volume contraction rate: the divergence of the vector field (−2ζ
//   for the linear impact oscillator) plus Σ ln |det S| over the impacts
//   (det S = r² for a Newton impact on a fixed stop: S = [[−r, 0], [·, −r]])
//   over the run time, the impacts those of the tangent run itself; also on
//   the 4-state model file in that chaos (divergence −2ζ − 2ζ₂);
// * on orbits with a sticking phase, the directions the contact collapses
//   (here all of them: a ball riding on the table) are −∞, never NaN;
// * the linear impact oscillator's orbit with every stepper, the Taylor
//   stepper's variational equations on multi-direction duals included;
// * λ1 is the largest exponent of largest_lyapunov_exponent on the same
//   trajectory, to 1e-10 (1/time unit): the QR carries its first vector as
//   that method carries its one vector, so they differ by round-off only.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/lyapunov_spectrum.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>
#include <impactlab/simulate/flow.hpp>

#include "support/linear_impact_closed_form.hpp"
#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;
using Complex = std::complex<double>;
constexpr double two_pi = 2.0 * std::numbers::pi;
constexpr double minus_infinity = -std::numeric_limits<double>::infinity();

const FlowSetup exact_flow{"exact", 1e-12, 1e-13};
const FlowSetup tight{"rk8pd", 1e-13, 1e-14};

// the state after `periods` forcing periods from (t0, x)
template <class System>
typename System::State after(const System& system, const FlowSetup& setup,
                             typename System::State x, typename System::Mode mode, double t0,
                             double t1, EventLog& log) {
  const auto run = with_flow<System>(setup.method, stepper_settings(system, setup),
                                     [&](auto& stepper) {
                                       return simulate(system, stepper, x, mode, t0, t1,
                                                       loop_options(setup), log);
                                     });
  EXPECT_EQ(run.termination, Termination::completed);
  return run.state;
}

// --- stable periodic orbits: λ_i = ln |μ_i| / T ---

// The linear impact oscillator's period-1 orbit at ω = 2.263, just below its
// period doubling (ω ≈ 2.2653: real, distinct multipliers), in closed form:
// its multipliers, its period and its state at t = 0 on the orbit.
struct ClosedFormOrbit {
  LinearImpactParameters parameters;
  std::array<std::complex<double>, 2> multipliers;
  double period;
  double x, v;
};

std::optional<ClosedFormOrbit> orbit_below_the_doubling() {
  LinearImpactParameters p;
  p.omega = 2.263;
  const impactlab::testing::LinearImpactClosedForm closed(p);
  const auto orbit = closed.orbit();
  if (!orbit || orbit->multipliers[1].imag() != 0.0) return std::nullopt;
  const double period = closed.period();
  const auto [x, v] =
      closed.state_after(orbit->impact_time, orbit->velocity, period - orbit->impact_time);
  return ClosedFormOrbit{p, {orbit->multipliers[0], orbit->multipliers[1]}, period, x, v};
}

TEST(LyapunovSpectrum, LinearImpactPeriodicOrbitGivesItsFloquetExponents) {
  const auto orbit = orbit_below_the_doubling();
  ASSERT_TRUE(orbit.has_value());
  const double period = orbit->period;
  const double x = orbit->x, v = orbit->v;
  const LinearImpact system(orbit->parameters);
  const auto spectrum = lyapunov_spectrum(system, exact_flow, LinearImpact::State{x, v},
                                          LinearImpact::Mode::free, 0.0, period, 400, 100);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  ASSERT_EQ(spectrum.exponents.size(), 2u);
  EXPECT_EQ(spectrum.periods, 400);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(spectrum.exponents[i], std::log(std::abs(orbit->multipliers[i])) / period, 1e-6)
        << "exponent " << i + 1;
    EXPECT_GE(spectrum.errors[i], 0.0);
    EXPECT_LT(spectrum.errors[i], 1e-3);
  }
}

// The same orbit with every stepper: the variational equations of each (the
// Taylor stepper's on multi-direction duals) and the QR give its exponents,
// and λ1 is the largest exponent of the same stepper.
class EveryStepper : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryStepper, LinearImpactPeriodicOrbitGivesItsFloquetExponents) {
  const auto orbit = orbit_below_the_doubling();
  ASSERT_TRUE(orbit.has_value());
  const double period = orbit->period;
  const double x = orbit->x, v = orbit->v;
  const LinearImpact system(orbit->parameters);
  const FlowSetup setup{GetParam(), 1e-12, 1e-13};
  const auto spectrum = lyapunov_spectrum(system, setup, LinearImpact::State{x, v},
                                          LinearImpact::Mode::free, 0.0, period, 300, 100);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(spectrum.exponents[i], std::log(std::abs(orbit->multipliers[i])) / period, 1e-6)
        << "exponent " << i + 1;
  const auto largest = largest_lyapunov_exponent(system, setup, LinearImpact::State{x, v},
                                                 LinearImpact::Mode::free, 0.0, period, 300, 100);
  EXPECT_NEAR(spectrum.exponents[0], largest.exponent, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, EveryStepper,
                         ::testing::Values("dopri5", "rkf78", "bulirsch_stoer", "rk8pd", "taylor",
                                           "exact"));

// The bouncing ball's period-1 orbit (one bounce per table period T = 2π/ω)
// and its multipliers, in closed form. The ball leaves the table z = A sin ωt
// at t* with ẏ⁺ = gT/2 and lands after exactly T at the same height, with
// ẏ⁻ = −gT/2; Newton's law (ẏ − ż)⁺ = −r(ẏ − ż)⁻ then needs
// ż(t*) = gT(1 − r)/(2(1 + r)). The impact map's Jacobian: the flight time τ
// solves F = z(t) + v τ − gτ²/2 − z(t + τ) = 0, so ∂τ/∂t = −F_t/F_τ = 0 on the
// orbit (ż(t) = ż(t + τ)) and ∂τ/∂v = −τ/F_τ with F_τ = v − gτ − ż(t + τ);
// v' = (1 + r) ż(t') − r (v − gτ) differentiates to
//     [[1, τ_v], [(1 + r) z̈, (1 + r) z̈ τ_v − r (1 − g τ_v)]].
struct BallOrbit {
  double takeoff_time;  // t* in [0, T) (s)
  std::array<Complex, 2> multipliers;
};

BallOrbit ball_orbit(const BouncingBallParameters& p, bool decelerating_table) {
  const double period = two_pi / p.omega;
  const double launch = p.g * period / 2.0;
  const double table_velocity = launch * (1.0 - p.r) / (1.0 + p.r);
  const double phase = std::acos(table_velocity / (p.A * p.omega));
  const double takeoff = (decelerating_table ? phase : two_pi - phase) / p.omega;
  const double table_acceleration = -p.A * p.omega * p.omega * std::sin(p.omega * takeoff);
  const double tau_v = period / (launch + table_velocity);  // −τ / F_τ
  const double m11 = 1.0, m12 = tau_v, m21 = (1.0 + p.r) * table_acceleration;
  const double m22 = (1.0 + p.r) * table_acceleration * tau_v - p.r * (1.0 - p.g * tau_v);
  const double trace = m11 + m22, determinant = m11 * m22 - m12 * m21;
  const Complex root = std::sqrt(Complex(trace * trace / 4.0 - determinant));
  BallOrbit orbit{takeoff, {trace / 2.0 + root, trace / 2.0 - root}};
  if (std::abs(orbit.multipliers[1]) > std::abs(orbit.multipliers[0]))
    std::swap(orbit.multipliers[0], orbit.multipliers[1]);
  return orbit;
}

TEST(LyapunovSpectrum, BouncingBallPeriodicOrbitGivesItsFloquetExponents) {
  // r = 0.5, Γ = Aω²/g ≈ 1.47: real multipliers ≈ −0.71 and −0.35
  BouncingBallParameters p;
  p.r = 0.5;
  p.A = 0.016;
  const BallOrbit orbit = ball_orbit(p, true);
  ASSERT_EQ(orbit.multipliers[0].imag(), 0.0);
  ASSERT_LT(std::abs(orbit.multipliers[0]), 1.0);
  EXPECT_NEAR(std::abs(orbit.multipliers[0] * orbit.multipliers[1]), p.r * p.r, 1e-12);
  const double period = two_pi / p.omega;
  // half a flight after the take-off: at the top of the parabola
  const BouncingBall system(p);
  const double t0 = orbit.takeoff_time + period / 2.0;
  const double launch = p.g * period / 2.0;
  const BouncingBall::State top{system.table_position(orbit.takeoff_time) +
                                    launch * launch / (2.0 * p.g),
                                0.0};
  const auto spectrum = lyapunov_spectrum(system, exact_flow, top, BouncingBall::Mode::free, t0,
                                          period, 400, 60);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  for (int i = 0; i < 2; ++i)
    EXPECT_NEAR(spectrum.exponents[i], std::log(std::abs(orbit.multipliers[i])) / period, 1e-6)
        << "exponent " << i + 1;
  const auto largest = largest_lyapunov_exponent(system, exact_flow, top,
                                                 BouncingBall::Mode::free, t0, period, 400, 60);
  EXPECT_NEAR(spectrum.exponents[0], largest.exponent, 1e-10);
}

// The linear impact oscillator (ζ = 0.05, A = 1, σ = 0.2, r = 0.8) and,
// uncoupled, u'' + 2ζ₂u' + u = 0 with ζ₂ = 1.25 (overdamped: real multipliers),
// as a 4-state model file.
constexpr const char* four_state_model = R"toml(name = "linear_impact_beside_overdamped_oscillator"
description = "the linear impact oscillator and an uncoupled overdamped oscillator (test)"

[initial]
x = 0.0
x_dot = 0.0
u = 0.0
u_dot = 0.0

[integrator]
method = "rk8pd"
rtol = 1e-12
atol = 1e-13

[model]
states = ["x", "x_dot", "u", "u_dot"]
forcing_frequency = "omega"
max_step = "2*pi/omega/16"

[model.parameters]
zeta  = { default = 0.05, min = 0.0 }
A     = { default = 1.0 }
omega = { default = 2.263, min = 0.0, min_open = true }
sigma = { default = 0.2 }
r     = { default = 0.8, min = 0.0, max = 1.0 }
zeta2 = { default = 1.25, min = 1.0 }

[model.rhs]
x = "x_dot"
x_dot = "A*cos(omega*t) - 2*zeta*x_dot - x"
u = "u_dot"
u_dot = "-2*zeta2*u_dot - u"

[[model.walls]]
name = "stop"
side = 1
witness = "sigma - x"
direction = "falling"
reset = { velocity = "x_dot", restitution = "r", position = "x" }
)toml";

// The 4-state model at its defaults, with ω given.
ModelSystem<4> four_state_system(double omega) {
  static const impactlab::testing::ScratchFolder folder;
  static const auto model = [] {
    const auto file = folder / "four_state.toml";
    std::ofstream(file) << four_state_model;
    CompileOptions options;
    options.cache_directory = (folder / "cache").string();
    return compile_model(read_model_file(file.string()), options);
  }();
  std::vector<double> parameters;
  for (const auto& parameter : model->parameters)
    parameters.push_back(parameter.name == "omega" ? omega : parameter.default_value);
  return ModelSystem<4>(model, parameters);
}

TEST(LyapunovSpectrum, FourStateModelPeriodicOrbitGivesItsFloquetExponents) {
  const ModelSystem<4> system = four_state_system(2.263);

  const auto orbit = orbit_below_the_doubling();
  ASSERT_TRUE(orbit.has_value());
  const double period = orbit->period;
  const double x = orbit->x, v = orbit->v;
  const double zeta2 = 1.25, root = std::sqrt(zeta2 * zeta2 - 1.0);
  // ln |μ| / T of each pair: the impact oscillator's, then the free pair's
  // (−ζ₂ + √(ζ₂² − 1) = −0.5, −ζ₂ − √(ζ₂² − 1) = −2)
  std::vector<double> expected = {std::log(std::abs(orbit->multipliers[0])) / period,
                                  std::log(std::abs(orbit->multipliers[1])) / period,
                                  -zeta2 + root, -zeta2 - root};
  std::sort(expected.begin(), expected.end(), std::greater<>());
  // the free pair starts off its rest state, so that both of its directions
  // are excited; it decays towards u = 0 without touching the orbit
  const auto spectrum = lyapunov_spectrum(system, tight, ModelSystem<4>::State{x, v, 0.0, 0.0},
                                          ModelSystem<4>::free_mode, 0.0, period, 400, 100);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  ASSERT_EQ(spectrum.exponents.size(), 4u);
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(spectrum.exponents[i], expected[i], 1e-6) << "exponent " << i + 1;
  const auto largest = largest_lyapunov_exponent(system, tight, ModelSystem<4>::State{x, v, 0, 0},
                                                 ModelSystem<4>::free_mode, 0.0, period, 400, 100);
  EXPECT_NEAR(spectrum.exponents[0], largest.exponent, 1e-10);
}

// --- chaotic orbits: the sum is the phase-volume contraction rate ---

TEST(LyapunovSpectrum, LinearImpactChaosSumsToThePhaseVolumeContraction) {
  for (const double omega : {2.5, 2.6}) {
    LinearImpactParameters p;
    p.omega = omega;
    const LinearImpact system(p);
    const double period = two_pi / omega;
    EventLog transient_log(false);
    const LinearImpact::State start = after(system, exact_flow, {0.0, 0.0},
                                            LinearImpact::Mode::free, 0.0, 200 * period,
                                            transient_log);
    const int periods = 400;
    const double t0 = 200 * period;
    // the attractor has no contact phase (a run of the base system alone)
    EventLog window(false);
    after(system, exact_flow, start, LinearImpact::Mode::free, t0, t0 + periods * period, window);
    ASSERT_EQ(window.count(EventKind::contact_start), 0u) << omega;

    const auto spectrum = lyapunov_spectrum(system, exact_flow, start, LinearImpact::Mode::free,
                                            t0, period, periods, 0);
    ASSERT_EQ(spectrum.termination, Termination::completed);
    // the impacts of the tangent run itself: on a chaotic orbit another run
    // of the same start parts from it within a few dozen periods
    const auto impacts = static_cast<double>(spectrum.impacts);
    ASSERT_GT(impacts, 100.0);
    const double contraction =
        -2.0 * p.zeta + impacts * std::log(p.r * p.r) / (periods * period);
    EXPECT_GT(spectrum.exponents[0], 0.05) << "not chaotic at omega = " << omega;
    EXPECT_NEAR(spectrum.exponents[0] + spectrum.exponents[1], contraction,
                1e-9 * std::fabs(contraction))
        << omega;
    // λ1 against the largest exponent alone, on the same trajectory
    const auto largest = largest_lyapunov_exponent(system, exact_flow, start,
                                                   LinearImpact::Mode::free, t0, period,
                                                   periods, 0);
    EXPECT_NEAR(spectrum.exponents[0], largest.exponent, 1e-10) << omega;
  }
}

TEST(LyapunovSpectrum, FourStateModelChaosSumsToThePhaseVolumeContraction) {
  // the linear impact oscillator's chaos at ω = 2.6 beside the overdamped
  // pair: divergence −2ζ − 2ζ₂, det S = r² per impact
  const double omega = 2.6, zeta = 0.05, zeta2 = 1.25, r = 0.8;
  const ModelSystem<4> system = four_state_system(omega);
  const double period = two_pi / omega;
  EventLog transient(false);
  const auto start = after(system, tight, {0.0, 0.0, 0.3, 0.0}, ModelSystem<4>::free_mode, 0.0,
                           100 * period, transient);
  const int periods = 300;
  const auto spectrum = lyapunov_spectrum(system, tight, start, ModelSystem<4>::free_mode,
                                          100 * period, period, periods, 10);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  ASSERT_GT(spectrum.impacts, 100u);
  EXPECT_GT(spectrum.exponents[0], 0.05);
  double sum = 0.0;
  for (double exponent : spectrum.exponents) sum += exponent;
  const double contraction = -2.0 * zeta - 2.0 * zeta2 +
                             static_cast<double>(spectrum.impacts) * std::log(r * r) /
                                 (periods * period);
  EXPECT_NEAR(sum, contraction, 1e-8 * std::fabs(contraction));
  // the free pair's faster exponent, −ζ₂ − √(ζ₂² − 1) = −2, well below the
  // others (its slower one, −0.5, lies 0.05 from the chaos's λ2 ≈ −0.45 and
  // separates from it only over many more periods)
  EXPECT_NEAR(spectrum.exponents[3], -2.0, 1e-3);
}

// --- sticking: the collapsed directions are −∞ ---

TEST(LyapunovSpectrum, BallRidingOnTheTableCollapsesEveryDirection) {
  // Γ ≈ 0.46: the ball rides on the table for good
  BouncingBallParameters p;
  p.A = 0.005;
  const BouncingBall system(p);
  const double period = two_pi / p.omega;
  const BouncingBall::State riding{system.table_position(0.0), system.table_velocity(0.0)};
  const auto spectrum = lyapunov_spectrum(system, exact_flow, riding, BouncingBall::Mode::stuck,
                                          0.0, period, 20, 2);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(spectrum.exponents[i], minus_infinity) << "exponent " << i + 1;
    EXPECT_EQ(spectrum.errors[i], 0.0);
  }
}

TEST(LyapunovSpectrum, BallThatChattersStickingEveryPeriodCollapsesEveryDirection) {
  // r = 0.3, Γ ≈ 1.38: thrown up by the table each period, the ball lands,
  // chatters to rest and rides until the table decelerates faster than g
  BouncingBallParameters p;
  p.r = 0.3;
  p.A = 0.015;
  const BouncingBall system(p);
  const double period = two_pi / p.omega;
  EventLog transient(false);
  const auto start = after(system, exact_flow, {0.05, 0.0}, BouncingBall::Mode::free, 0.0,
                           50 * period, transient);
  EventLog window(false);
  after(system, exact_flow, start, BouncingBall::Mode::free, 50 * period, 70 * period, window);
  ASSERT_GE(window.count(EventKind::contact_start), 10u);
  ASSERT_GE(window.count(EventKind::contact_end), 10u);

  std::vector<std::vector<double>> rows;
  struct Rows final : LyapunovSpectrumSink {
    std::vector<std::vector<double>>& rows;
    explicit Rows(std::vector<std::vector<double>>& r) : rows(r) {}
    void begin(std::size_t exponents) override { EXPECT_EQ(exponents, 2u); }
    void write(double, const std::vector<double>& running) override { rows.push_back(running); }
  } sink(rows);
  const auto spectrum = lyapunov_spectrum(system, exact_flow, start, BouncingBall::Mode::free,
                                          50 * period, period, 20, 2, &sink);
  ASSERT_EQ(spectrum.termination, Termination::completed);
  ASSERT_EQ(rows.size(), 20u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(spectrum.exponents[i], minus_infinity) << "exponent " << i + 1;
    for (const auto& row : rows) EXPECT_FALSE(std::isnan(row[i]));
  }
  const auto largest = largest_lyapunov_exponent(system, exact_flow, start,
                                                 BouncingBall::Mode::free, 50 * period, period,
                                                 20, 2);
  EXPECT_EQ(largest.exponent, minus_infinity);
}

// --- the running estimate and its spread ---

TEST(LyapunovSpectrum, RunningSpreadIsHalfTheRangeOverTheLastQuarter) {
  RunningSpread spread(2, 8);  // periods 7 and 8 are the last quarter
  for (int period = 1; period <= 8; ++period)
    spread.add(period, {period == 7 ? 1.0 : period == 8 ? 1.5 : 100.0, -1.0});
  const auto half = spread.half_ranges({1.5, minus_infinity});
  EXPECT_DOUBLE_EQ(half[0], 0.25);
  EXPECT_EQ(half[1], 0.0);
}

TEST(LyapunovSpectrum, AccumulatorStartsAlongTheLargestExponentsVector) {
  // J = diag(2, 1/2, 1) in one period of length 1: the first vector
  // (1, 1, 1)/√3 is stretched to |J v| = √(4 + 1/4 + 1)/√3
  LyapunovSpectrumAccumulator accumulator(3, 1.0);
  const double jacobian[9] = {2.0, 0, 0, 0, 0.5, 0, 0, 0, 1.0};
  ASSERT_TRUE(accumulator.advance(jacobian, true));
  const auto first = accumulator.exponents();
  EXPECT_NEAR(first[0], std::log(std::sqrt(5.25 / 3.0)), 1e-15);
  // the three stretches multiply to det J = 1
  EXPECT_NEAR(first[0] + first[1] + first[2], 0.0, 1e-14);
  // after many periods: ln 2, 0, ln 1/2, in that order
  for (int k = 0; k < 2000; ++k) accumulator.advance(jacobian, true);
  const auto late = accumulator.exponents();
  EXPECT_NEAR(late[0], std::log(2.0), 1e-3);
  EXPECT_NEAR(late[1], 0.0, 1e-3);
  EXPECT_NEAR(late[2], std::log(0.5), 1e-3);
  const double singular[9] = {1.0, 0, 0, 0, 0, 0, 0, 0, 1.0};
  ASSERT_TRUE(accumulator.advance(singular, true));
  EXPECT_EQ(accumulator.exponents()[2], minus_infinity);
  const double broken[9] = {NAN, 0, 0, 0, 1, 0, 0, 0, 1};
  EXPECT_FALSE(accumulator.advance(broken, true));
}

TEST(LyapunovSpectrum, RankOneJacobianCollapsesTwoDirectionsBelowRoundOff) {
  // J = u vᵀ, rank 1: a contact that pins two of three directions, then a
  // flight that mixes what is left into every component. The QR's round-off
  // leaves |R_22|, |R_33| at about 1e-16 of |R_11|, not exactly zero;
  // collapse_tolerance tells them from a contraction.
  LyapunovSpectrumAccumulator accumulator(3, 2.0);
  const double u[3] = {0.3, -1.7, 0.9}, v[3] = {1.1, 0.4, -0.7};
  double pinned[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) pinned[3 * i + j] = u[i] * v[j];
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(accumulator.advance(pinned, true));
  const auto exponents = accumulator.exponents();
  EXPECT_TRUE(std::isfinite(exponents[0]));
  EXPECT_EQ(exponents[1], minus_infinity);
  EXPECT_EQ(exponents[2], minus_infinity);
  // a strong but resolved contraction, 1e-9 per period, stays finite
  LyapunovSpectrumAccumulator resolved(2, 1.0);
  const double contracting[4] = {1.0, 0.0, 0.0, 1e-9};
  for (int k = 0; k < 2; ++k) ASSERT_TRUE(resolved.advance(contracting, false));  // align
  for (int k = 0; k < 50; ++k) ASSERT_TRUE(resolved.advance(contracting, true));
  EXPECT_NEAR(resolved.exponents()[1], std::log(1e-9), 1e-6);
}

}  // namespace
