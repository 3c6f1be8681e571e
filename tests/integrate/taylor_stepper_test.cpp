// The Taylor-series stepper (integrate/taylor_stepper.hpp) and its parts:
// * the series arithmetic (integrate/taylor_series.hpp) against Taylor
//   coefficients known in closed form, or against the function itself;
// * the polynomial root isolation (integrate/polynomial_roots.hpp) on root
//   pairs far closer than any sampling grid;
// * whole runs against closed-form flows (the linear impact oscillator's
//   exact flow), with steps far longer than the systems' max_step;
// * the size of a bookkeeping component does not move the motion;
// * systems whose right-hand side is not written over a number type are
//   refused with a clear error.
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/polynomial_roots.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/integrate/taylor_series.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;
constexpr double pi = std::numbers::pi;

double factorial(int k) {
  double f = 1.0;
  for (int j = 2; j <= k; ++j) f *= j;
  return f;
}

// Coefficients 0..order of a right-hand side written in the test, over
// TaylorVariable, with up to TaylorSeries::max_outputs further series
template <std::size_t N, class Rhs>
TaylorSeries<double, N> series_of(const std::array<double, N>& x0, double t0, int order, Rhs rhs) {
  TaylorSeries<double, N> series;
  series.evaluate(x0.data(), t0, order, rhs);
  return series;
}

// x' = sin(a + b t): the series of sin(a + b t) and cos(a + b t) (the
// one-term recurrence of a linear argument) against the closed forms
TEST(TaylorSeries, SinCosOfAffineArgumentMatchClosedForm) {
  const double a = 0.7, b = 2.5;
  const double t0 = 0.3;
  const int order = 20;
  using V = TaylorVariable<double>;
  const auto series = series_of<1>({0.0}, t0, order, [&](const std::array<V, 1>&, const V& t,
                                                        std::array<V, 1>& dxdt, auto& outputs) {
    const V s = sin(a + b * t);
    const V c = cos(a + b * t);
    dxdt[0] = s;
    outputs[0] = s;
    outputs[1] = c;
    return 2;
  });
  const double* sk = series.output(0);
  const double* ck = series.output(1);
  const double* xk = series.state(0);
  const double phase = a + b * t0;
  for (int k = 0; k <= order; ++k) {
    // d^k/dt^k sin(a + b t) = b^k sin(phase + k π/2)
    const double expected_s = std::pow(b, k) * std::sin(phase + k * pi / 2) / factorial(k);
    const double expected_c = std::pow(b, k) * std::cos(phase + k * pi / 2) / factorial(k);
    // round-off grows by about one ulp per order in both the recurrence and
    // the closed form (k π / 2)
    const double scale = std::pow(b, k) / factorial(k);
    EXPECT_NEAR(sk[k], expected_s, 4e-16 * (k + 1) * scale) << k;
    EXPECT_NEAR(ck[k], expected_c, 4e-16 * (k + 1) * scale) << k;
    // x' = sin(a + b t), x(t0) = 0: x_{k+1} = s_k / (k + 1)
    if (k < order) {
      EXPECT_DOUBLE_EQ(xk[k + 1], sk[k] / (k + 1)) << k;
    }
  }
}

// x' = x², x(0) = 1: x = 1 / (1 − t), every coefficient 1; and
// y' = −y / (1 + t), y(0) = 1: y = 1 / (1 + t), coefficients ±1
TEST(TaylorSeries, ProductAndQuotientRecurrences) {
  using V = TaylorVariable<double>;
  const auto series = series_of<2>({1.0, 1.0}, 0.0, 25, [](const std::array<V, 2>& x, const V& t,
                                                           std::array<V, 2>& dxdt, auto&) {
    dxdt = {x[0] * x[0], -x[1] / (1.0 + t)};
    return 0;
  });
  for (int k = 0; k <= 25; ++k) {
    EXPECT_NEAR(series.state(0)[k], 1.0, 1e-13) << k;
    EXPECT_NEAR(series.state(1)[k], k % 2 == 0 ? 1.0 : -1.0, 1e-13) << k;
  }
}

// sin of a state variable (the coupled recurrence with the state's rates)
// and of a general series (x0², with its own row of j a_j): x' = 1 with
// x(0) = x0 gives sin x = sin(x0 + t) and sin x² = sin((x0 + t)²)
TEST(TaylorSeries, SinOfSeriesArgumentByCoupledRecurrence) {
  using V = TaylorVariable<double>;
  const double x0 = 0.4;
  const int order = 18;
  const auto series = series_of<2>({x0, 0.0}, 0.0, order, [](const std::array<V, 2>& x, const V&,
                                                             std::array<V, 2>& dxdt, auto& outputs) {
    dxdt = {V(1.0), sin(x[0] * x[0])};
    outputs[0] = sin(x[0]);
    return 1;
  });
  const double* sk = series.output(0);
  for (int k = 0; k <= order; ++k)
    EXPECT_NEAR(sk[k], std::sin(x0 + k * pi / 2) / factorial(k), 1e-15) << k;
  // y' = sin((x0 + t)²): the derivative of y's polynomial, Σ k y_k h^{k−1},
  // against sin((x0 + h)²) itself at points of the step (an entire
  // function: the truncation error at h ≤ 0.2 is far below the tolerance)
  const double* yk = series.state(1);
  for (double h : {0.05, 0.1, 0.2}) {
    double derivative = 0.0, power = 1.0;
    for (int k = 1; k <= order; ++k) {
      derivative += k * yk[k] * power;
      power *= h;
    }
    EXPECT_NEAR(derivative, std::sin((x0 + h) * (x0 + h)), 1e-12) << h;
  }
}

// exp, log, √ and constant powers of a state component (x' = 1, x(0) = 0,
// so x = t with every degree of a state) and of the time itself (degree 1)
// against their closed-form series: e^{1/2} 2^k / k!, (−1)^{k+1} / k, and
// the binomial coefficients (α over k) of (1 + h)^α.
TEST(TaylorSeries, ExpLogSqrtAndPowersMatchTheirClosedFormSeries) {
  using V = TaylorVariable<double>;
  const int order = 24;
  const auto series = series_of<1>({0.0}, 0.0, order, [](const std::array<V, 1>& x, const V& t,
                                                        std::array<V, 1>& dxdt, auto& outputs) {
    dxdt[0] = V(1.0);
    outputs[0] = exp(0.5 + 2.0 * x[0]);
    outputs[1] = log(1.0 + x[0]);
    outputs[2] = sqrt(1.0 + x[0]);
    outputs[3] = pow(1.0 + x[0], 2.5);
    outputs[4] = pow(1.0 + 0.5 * t, -1.5);
    outputs[5] = exp(0.5 + 2.0 * t);
    return 6;
  });
  const auto binomial = [](double alpha, int k) {
    double c = 1.0;
    for (int i = 0; i < k; ++i) c *= (alpha - i) / (i + 1);
    return c;
  };
  for (int k = 0; k <= order; ++k) {
    SCOPED_TRACE("order " + std::to_string(k));
    const double tolerance = 1e-15 * (k + 1);
    const double e = std::exp(0.5) * std::pow(2.0, k) / factorial(k);
    EXPECT_NEAR(series.output(0)[k], e, tolerance * e);
    EXPECT_NEAR(series.output(5)[k], e, tolerance * e);
    EXPECT_NEAR(series.output(1)[k], k == 0 ? 0.0 : (k % 2 == 1 ? 1.0 : -1.0) / k, tolerance);
    EXPECT_NEAR(series.output(2)[k], binomial(0.5, k), tolerance);
    EXPECT_NEAR(series.output(3)[k], binomial(2.5, k), tolerance);
    EXPECT_NEAR(series.output(4)[k], binomial(-1.5, k) * std::pow(0.5, k),
                tolerance * std::fabs(binomial(-1.5, k)) * std::pow(0.5, k));
  }
}

// More operations than the series has rows: a clear error, not an overrun
TEST(TaylorSeries, TooManyOperationsAreRefused) {
  using V = TaylorVariable<double>;
  auto run = [] {
    series_of<1>({1.0}, 0.0, 4, [](const std::array<V, 1>& x, const V&, std::array<V, 1>& dxdt,
                                   auto&) {
      V sum = x[0];
      for (int i = 0; i < 400; ++i) sum = sum * x[0];
      dxdt[0] = sum;
      return 0;
    });
  };
  EXPECT_THROW(run(), std::length_error);
}

// (h − 1/2)² − δ² has the roots 1/2 ± δ; with δ = 1e-7 no sampling of [0, 1]
// coarser than 2e-7 separates them. (h − 1/2)² + δ² has none.
TEST(PolynomialRoots, CloseRootPairIsSeparatedAndNearMissIsNot) {
  const double delta = 1e-7;
  const std::array<double, 3> pair = {0.25 - delta * delta, -1.0, 1.0};
  const PolynomialRoots<8> p(pair.data(), 2, 1.0);
  const auto roots = p.sign_changes(0, 0.0, 1.0);
  ASSERT_EQ(roots.count, 2);
  // the slope there is ±2δ and the polynomial's round-off about 1e-17: the
  // roots are determined in double to about 1e-17 / 2δ = 5e-11
  EXPECT_NEAR(roots.points[0], 0.5 - delta, 1e-9);
  EXPECT_NEAR(roots.points[1], 0.5 + delta, 1e-9);

  const std::array<double, 3> miss = {0.25 + delta * delta, -1.0, 1.0};
  const PolynomialRoots<8> q(miss.data(), 2, 1.0);
  EXPECT_EQ(q.sign_changes(0, 0.0, 1.0).count, 0);
  const auto critical = q.sign_changes(1, 0.0, 1.0);
  ASSERT_EQ(critical.count, 1);
  EXPECT_NEAR(critical.points[0], 0.5, 1e-15);
}

// the coefficients of the degree-9 polynomial (h − 0.1)(h − 0.2)…(h − 0.9)
std::array<double, 10> product_with_roots_at_tenths() {
  std::array<double, 10> c{};
  c[0] = 1.0;
  for (int r = 1; r <= 9; ++r) {
    // multiply by (h − r/10)
    for (int j = r; j >= 0; --j) c[j] = (j > 0 ? c[j - 1] : 0.0) - 0.1 * r * c[j];
  }
  return c;
}

// a degree-9 polynomial with roots at 0.1, 0.2, ..., 0.9: all nine found
TEST(PolynomialRoots, AllRootsOfAProductInOrder) {
  const std::array<double, 10> c = product_with_roots_at_tenths();
  const PolynomialRoots<12> p(c.data(), 9, 1.0);
  const auto roots = p.sign_changes(0, 0.0, 0.95);
  ASSERT_EQ(roots.count, 9);
  // the coefficients carry round-off, amplified ~1e4 times by these
  // clustered roots (Wilkinson)
  for (int r = 1; r <= 9; ++r) EXPECT_NEAR(roots.points[r - 1], 0.1 * r, 1e-10) << r;
}

// Visiting the roots stops where the visitor says, after the same numbers
// sign_changes gives, in the same order
TEST(PolynomialRoots, VisitingStopsAfterTheSameLeadingRoots) {
  const std::array<double, 10> c = product_with_roots_at_tenths();
  const PolynomialRoots<12> p(c.data(), 9, 1.0);
  const auto all = p.sign_changes(0, 0.0, 0.95);
  ASSERT_EQ(all.count, 9);
  std::vector<double> seen;
  const bool stopped = p.visit_sign_changes(0, 0.0, 0.95, [&seen](double root) {
    seen.push_back(root);
    return seen.size() == 3;
  });
  EXPECT_TRUE(stopped);
  ASSERT_EQ(seen.size(), 3U);
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], all.points[i]) << i;
  seen.clear();
  EXPECT_FALSE(p.visit_sign_changes(0, 0.0, 0.95, [&seen](double root) {
    seen.push_back(root);
    return false;
  }));
  EXPECT_EQ(seen.size(), 9U);
}

// Free flight of the damped, forced linear oscillator against its closed-form
// flow (LinearImpact::exact_flow), with the stop far away: the error at
// t = 40 falls with the tolerance and is at the tolerance's level.
TEST(TaylorStepper, LinearOscillatorMatchesClosedFormFlow) {
  LinearImpactParameters p;
  p.zeta = 0.05;
  p.A = 0.7;
  p.omega = 1.3;
  p.sigma = 100.0;
  const LinearImpact system(p);
  const LinearImpact::State x0 = {0.2, -0.4};
  LinearImpact::State exact;
  system.exact_flow(LinearImpact::Mode::free, x0, 0.0, 40.0, exact);
  double previous_error = INFINITY;
  for (const double tolerance : {1e-8, 1e-11, 1e-14}) {
    StepperSettings settings;
    settings.rtol = settings.atol = tolerance;
    settings.max_step = system.max_step();
    EventLog log;
    TaylorStepper<LinearImpact> stepper(settings);
    const auto result = simulate(system, stepper, x0, LinearImpact::Mode::free, 0.0, 40.0,
                                 LoopOptions{}, log);
    const double error =
        std::max(std::fabs(result.state[0] - exact[0]), std::fabs(result.state[1] - exact[1]));
    EXPECT_LE(error, 200.0 * tolerance) << tolerance;
    EXPECT_LT(error, previous_error) << tolerance;
    previous_error = error;
    // no max_step cap: the steps are longer than the system's T/16
    EXPECT_LT(static_cast<double>(result.counters.steps), 40.0 / system.max_step()) << tolerance;
  }
}

// The jin2003 pendulum (V0 = 1.5 m/s, 200 forcing periods): the impact times
// agree with rkf78 at rtol 1e-13 (with its T/16 cap and re-taken steps) to
// 1e-9 s, the Taylor stepper running without any step cap.
TEST(TaylorStepper, PendulumImpactTimesAgreeWithRkf78) {
  PendulumWallsParameters p;
  p.V0 = 1.5;
  const PendulumWalls system(p);
  const double t_end = 200.0 * 2.0 * pi / p.omega;
  auto run = [&](std::string_view method, double rtol) {
    StepperSettings settings;
    settings.rtol = rtol;
    settings.atol = 1e-14;
    settings.max_step = system.max_step();
    EventLog log;
    const auto result = with_flow<PendulumWalls>(method, settings, [&](auto& stepper) {
      return simulate(system, stepper, PendulumWalls::State{0.0, 0.1, 0.0},
                      PendulumWalls::Mode::free, 0.0, t_end, LoopOptions{}, log);
    });
    EXPECT_EQ(result.termination, Termination::completed);
    return std::make_pair(result, log.records());
  };
  const auto [taylor, taylor_events] = run("taylor", 1e-12);
  const auto [reference, reference_events] = run("rkf78", 1e-13);
  ASSERT_GT(reference_events.size(), 150u);
  ASSERT_EQ(taylor_events.size(), reference_events.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < taylor_events.size(); ++i) {
    ASSERT_EQ(taylor_events[i].kind, reference_events[i].kind) << i;
    worst = std::max(worst, std::fabs(taylor_events[i].t - reference_events[i].t));
  }
  EXPECT_LE(worst, 1e-9);
  RecordProperty("taylor_steps", std::to_string(taylor.counters.steps));
}

// Model N's friction work is bookkeeping (core/error_scale_groups.hpp): a
// work of 1e6 J at the start, as a long run with sliding contacts gathers,
// leaves the motion exactly as it is with none. Measured in one group with
// the motion, it made the allowed error a million times the tolerance.
TEST(TaylorStepper, ABookkeepingComponentsSizeDoesNotMoveTheMotion) {
  PendulumWallsParameters p;
  p.V0 = 1.5;
  const PendulumWalls system(p);
  const double t_end = 50.0 * 2.0 * pi / p.omega;
  auto events_from = [&](double friction_work) {
    StepperSettings settings;
    settings.rtol = 1e-12;
    settings.atol = 1e-14;
    settings.max_step = system.max_step();
    EventLog log(true);
    TaylorStepper<PendulumWalls> stepper(settings);
    const auto result = simulate(system, stepper, PendulumWalls::State{0.0, 0.1, friction_work},
                                 PendulumWalls::Mode::free, 0.0, t_end, LoopOptions{}, log);
    EXPECT_EQ(result.termination, Termination::completed);
    return log.records();
  };
  const auto without = events_from(0.0), with_work = events_from(1e6);
  ASSERT_GT(without.size(), 30u);
  ASSERT_EQ(with_work.size(), without.size());
  for (std::size_t i = 0; i < without.size(); ++i) {
    EXPECT_EQ(with_work[i].t, without[i].t) << i;
    EXPECT_EQ(with_work[i].qdot_before, without[i].qdot_before) << i;
  }
}

// A system whose right-hand side takes doubles only
struct DoublesOnly {
  using State = std::array<double, 2>;
  enum class Mode { free };
  static constexpr std::size_t max_witnesses = 1;
  void rhs(Mode, const State& x, State& dxdt, double) const {
    dxdt[0] = x[1];
    dxdt[1] = -x[0];
  }
  [[nodiscard]] std::size_t witness_count(Mode) const { return 1; }
  [[nodiscard]] TriggerDirection trigger_direction(Mode, std::size_t) const {
    return TriggerDirection::falling;
  }
  [[nodiscard]] WitnessSample witness(Mode, std::size_t, const State& x, double) const {
    return {1.0 - x[0], -x[1]};
  }
  Transition<State, Mode> on_event(Mode, std::size_t, CrossingKind, const State& x, double t,
                                   EventLog&) const {
    return {x, Mode::free, t, false};
  }
  [[nodiscard]] double max_step() const { return 0.1; }
};
static_assert(!HasSeriesRhs<DoublesOnly>);
static_assert(HasSeriesRhs<PendulumWalls>);
static_assert(HasSeriesRhs<PaperPendulumWalls>);
static_assert(HasSeriesRhs<LinearImpact>);

TEST(TaylorStepper, SystemWithoutSeriesRhsIsRefusedByName) {
  StepperSettings settings;
  try {
    with_stepper<DoublesOnly>("taylor", settings, [](auto&) { return 0; });
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("integrator.method = taylor"), std::string::npos);
  }
}

}  // namespace
