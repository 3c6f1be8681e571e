// The hard cases of impact simulation, each against a closed form or an
// independent computation written here (the cost of each belongs to
// `impactlab bench`). Related cases elsewhere, not repeated here:
// * simulate/simulator_test.cpp: a grazing double root inside one step, a
//   pair of roots 1e-7 inside the stop, a near miss, an event at t0 and at
//   the end time on the linear oscillator, no event twice, the unresolved
//   Zeno stop;
// * oscillators/pendulum_walls_test.cpp: the contact phases of V0 = 4.163
//   (release times, friction work), the impacts before an accumulation
//   bounded, energy at e_n = 1, μ above and below the Painlevé limit;
// * oscillators/bouncing_ball_test.cpp: chattering at r = 0.5 into riding
//   and release.
//
// Cases here:
//   chattering to rest   BouncingBall r = 0.05; pendulum V0 = 4.163 (the
//                        geometric decay of each chatter sequence)
//   grazing              a sweep of the stop through the amplitude of the
//                        linear oscillator's non-impacting periodic orbit
//   e_n = 0, e_n = 1     plastic ball and pendulum; elastic linear oscillator
//   very small gaps      pendulum with walls 2b = 20 µm apart
//   high frequency       bouncing ball at ω = 3000 rad/s on its period-1 orbit
//   Painlevé limit       μ exactly at, just below and just above 1 / tan θ0
//   10^6 impacts         the period-1 bouncing ball: the count, no drift
//   t = 0 and t_end      pendulum starting on a wall; ball resting on the
//                        table at t0; pendulum impact exactly at t_end
//   hops << a step       the linear oscillator's chatter where its stop is
//                        about to let go
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

#include "support/linear_impact_chatter.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

constexpr double pi = std::numbers::pi;

const std::vector<std::string> all_steppers = {"dopri5", "rkf78", "bulirsch_stoer", "rk8pd",
                                               "taylor", "exact"};
const std::vector<std::string> numerical_steppers = {"dopri5", "rkf78", "bulirsch_stoer",
                                                     "rk8pd", "taylor"};

template <class System>
struct Run {
  RunResult<typename System::State, typename System::Mode> result;
  std::vector<EventRecord> events;
};

template <class System, class Observer = NoObserver>
Run<System> run(const System& system, std::string_view method, typename System::State x0,
                typename System::Mode mode, double t0, double t_end, double rtol = 1e-12,
                double atol = 1e-12, LoopOptions options = LoopOptions{},
                Observer&& observer = Observer{}) {
  StepperSettings settings;
  settings.rtol = rtol;
  settings.atol = atol;
  settings.max_step = system.max_step();
  EventLog log;
  Run<System> out;
  out.result = with_flow<System>(method, settings, [&](auto& stepper) {
    return simulate(system, stepper, x0, mode, t0, t_end, options, log,
                    std::forward<Observer>(observer));
  });
  out.events = log.records();
  return out;
}

std::vector<EventRecord> of_kind(const std::vector<EventRecord>& events, EventKind kind) {
  std::vector<EventRecord> selected;
  for (const auto& e : events)
    if (e.kind == kind) selected.push_back(e);
  return selected;
}

bool converged(double a, double b) {
  return std::fabs(b - a) <=
         4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(b));
}

template <class F>
double root_in(F&& f, double a, double b) {
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(f, a, b, converged, iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// Samples the ball's height over the table on a grid: the ball must never be
// below it by more than the grazing tolerance.
struct TableClearance {
  const BouncingBall* system;
  double spacing;  // s
  double t0;       // s
  long index = 0;
  double min_gap = INFINITY;  // m
  [[nodiscard]] double next_time() const { return t0 + static_cast<double>(index) * spacing; }
  template <class S, class M>
  void observe(double t, const S& x, M) {
    ++index;
    min_gap = std::min(min_gap, x[0] - system->table_position(t));
  }
};

class HardCaseExactFlow : public ::testing::TestWithParam<std::string> {};
class HardCasePendulum : public ::testing::TestWithParam<std::string> {};

// ---------------------------------------------------------------------------
// Chattering to rest, bouncing ball with small restitution r = 0.05 dropped
// from 5 cm onto the table of the defaults. Checks: the first impact where
// the closed-form parabola meets A sin ωt; every later impact of the
// sequence obeys Newton's law on the relative velocity; the impacts before
// the accumulation are few (the rule of contact/accumulation.hpp accepts the
// estimate once its error bound E = T0³ (½ (ȧ/a)² + ¼ |ä|/a), T0 = 2u/(a(1 − r)),
// is within the tolerance, and E shrinks by r³ per impact:
// n <= 1 + ceil(ln(tol / E_1) / (3 ln r))); the ball never
// goes below the table; it rides until the closed-form release, where the
// table's acceleration falls through −g (sin ωt = g / (A ω²)).
TEST_P(HardCaseExactFlow, SmallRestitutionChattersToRestOnTheTable) {
  BouncingBallParameters p;
  p.r = 0.05;
  const BouncingBall system(p);
  const double period = 2.0 * pi / p.omega;
  TableClearance clearance{&system, period / 500.0, 0.0};
  const auto r = run(system, GetParam(), {0.05, 0.0}, BouncingBall::Mode::free, 0.0, 2.0 * period,
                     1e-12, 1e-12, LoopOptions{}, clearance);
  ASSERT_EQ(r.result.termination, Termination::completed);
  EXPECT_GE(clearance.min_gap, -1e-12);

  // the first chatter sequence: the impacts before the first accumulation
  std::vector<EventRecord> impacts;
  std::size_t accumulation = 0;
  while (accumulation < r.events.size() && r.events[accumulation].kind == EventKind::impact)
    impacts.push_back(r.events[accumulation++]);
  ASSERT_GE(impacts.size(), 1u);
  ASSERT_LT(accumulation + 1, r.events.size());
  const double first =
      root_in([&](double t) { return 0.05 - 0.5 * p.g * t * t - p.A * std::sin(p.omega * t); },
              0.0, 0.2);
  EXPECT_NEAR(impacts[0].t, first, 1e-10);
  EXPECT_NEAR(impacts[0].qdot_before, -p.g * first, 1e-9);
  for (const auto& impact : impacts) {
    const double table_speed = p.A * p.omega * std::cos(p.omega * impact.t);
    EXPECT_NEAR(impact.qdot_after - table_speed, -p.r * (impact.qdot_before - table_speed), 1e-12);
  }
  // the first separation speed bounds the first estimate of the remaining
  // time; the table's motion makes the flights differ from the geometric
  // series, so (as in pendulum_walls_test) twice 1 + n is allowed
  const double u1 = p.r * std::fabs(impacts[0].qdot_before -
                                    p.A * p.omega * std::cos(p.omega * impacts[0].t));
  const double a1 = p.g - p.A * p.omega * p.omega * std::sin(p.omega * impacts[0].t);
  ASSERT_GT(a1, 0.0);
  const double t_rem1 = 2.0 * u1 / (a1 * (1.0 - p.r));
  const double a1_rate = -p.A * std::pow(p.omega, 3) * std::cos(p.omega * impacts[0].t);
  const double a1_curvature = p.A * std::pow(p.omega, 4) * std::sin(p.omega * impacts[0].t);
  const double bound1 = std::pow(t_rem1, 3) * (0.5 * std::pow(a1_rate / a1, 2) +
                                              0.25 * std::fabs(a1_curvature) / a1);
  const double n = std::max(
      0.0, std::ceil(std::log(p.accumulation.time / bound1) / (3.0 * std::log(p.r))));
  EXPECT_LE(static_cast<double>(impacts.size()), 2.0 * (1.0 + n));

  const EventRecord& acc = r.events[accumulation];
  const EventRecord& start = r.events[accumulation + 1];
  ASSERT_EQ(acc.kind, EventKind::accumulation);
  ASSERT_EQ(start.kind, EventKind::contact_start);
  EXPECT_EQ(start.t, acc.t);
  const auto ends = of_kind(r.events, EventKind::contact_end);
  ASSERT_GE(ends.size(), 1u);
  const auto starts = std::vector<EventRecord>{start};
  // release: the first time after the contact start with sin ωt = g/(Aω²), rising
  const double release_phase = std::asin(p.g / (p.A * p.omega * p.omega));
  double release = release_phase / p.omega;
  while (release < starts[0].t) release += period;
  EXPECT_NEAR(ends[0].t, release, 1e-9);
}

// Chattering to rest on the pendulum at V0 = 4.163 m/s (the paper's case):
// in a chatter sequence the normal acceleration is nearly constant over the
// short flights, so each flight returns the bob with the speed it left with
// and successive impact speeds fall by e_n: |θ̇⁻_{k+1}| / |θ̇⁻_k| → e_n.
// Checks, over 30 forcing periods (one long chatter sequence into contact
// early on): the run completes (no Zeno stop); every accumulation ends a
// sequence of impacts on its wall whose last two speed ratios are within 2 %
// of e_n; no impact after an accumulation and before its contact phase ends.
TEST_P(HardCasePendulum, ChatterSequencesDecayGeometricallyIntoContact) {
  PendulumWallsParameters p;
  p.V0 = 4.163;
  const PendulumWalls system(p);
  const auto r = run(system, GetParam(), {0.0, 0.1, 0.0}, PendulumWalls::Mode::free, 0.0,
                     30.0 * 2.0 * pi / p.omega, 1e-10, 1e-12);
  ASSERT_EQ(r.result.termination, Termination::completed);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    if (r.events[i].kind != EventKind::accumulation) continue;
    std::size_t first = i;
    while (first > 0 && r.events[first - 1].kind == EventKind::impact &&
           r.events[first - 1].wall == r.events[i].wall)
      --first;
    SCOPED_TRACE("accumulation at t = " + std::to_string(r.events[i].t));
    if (i - first < 3) continue;
    for (std::size_t k = i - 2; k < i; ++k) {
      const double ratio =
          std::fabs(r.events[k].qdot_before) / std::fabs(r.events[k - 1].qdot_before);
      EXPECT_NEAR(ratio, p.e_n, 0.02 * p.e_n) << "impact " << k;
    }
    ++checked;
    // the contact phase that follows has no impact inside it
    ASSERT_LT(i + 1, r.events.size());
    if (r.events[i + 1].kind != EventKind::contact_start) continue;
    for (std::size_t k = i + 2; k < r.events.size(); ++k) {
      if (r.events[k].kind == EventKind::contact_end) break;
      EXPECT_NE(r.events[k].kind, EventKind::impact) << "at t = " << r.events[k].t;
    }
  }
  EXPECT_GE(checked, 1u);
}

// ---------------------------------------------------------------------------
// Grazing bifurcation. Started on the non-impacting periodic orbit of
// ẍ + 2ζẋ + x = A cos ωt, x = R cos(ωt + φ) with R e^{iφ} = A / (1 − ω² + 2iζω),
// the mass reaches x = R once per forcing period with zero velocity there.
// Sweeping the stop σ through R: for σ > R no event at all over three
// touches (near misses down to a gap of 1e-9 R), for σ < R the first event is
// an impact at the closed-form time ωt + φ = −acos(σ/R) (mod 2π) with speed
// Rω √(1 − (σ/R)²). No missed and no spurious impacts at any σ.
TEST_P(HardCaseExactFlow, SweepThroughGrazingMissesNoImpactAndAddsNone) {
  LinearImpactParameters p;
  p.zeta = 0.05;
  p.A = 1.0;
  p.omega = 2.0;
  const std::complex<double> amplitude =
      p.A / std::complex<double>(1.0 - p.omega * p.omega, 2.0 * p.zeta * p.omega);
  const double R = std::abs(amplitude);
  const double phi = std::arg(amplitude);
  const double period = 2.0 * pi / p.omega;
  // on the orbit at t = 0: x = Re(R e^{iφ}), ẋ = Re(iω R e^{iφ})
  const LinearImpact::State x0{amplitude.real(),
                               (std::complex<double>(0.0, p.omega) * amplitude).real()};
  // the first phase ωt > 0 with ωt + φ ≡ −angle (mod 2π)
  auto first_time = [&](double angle) {
    double phase = -phi - angle;
    while (phase <= 0.0) phase += 2.0 * pi;
    return phase / p.omega;
  };
  const double t_end = first_time(0.0) + 2.25 * period;
  int cases = 0;
  for (double relative : {-1e-2, -1e-4, -1e-6, -1e-8, -1e-9, 1e-9, 1e-8, 1e-6, 1e-4, 1e-2}) {
    p.sigma = R * (1.0 + relative);
    ASSERT_LT(x0[0], p.sigma);
    const LinearImpact system(p);
    LoopOptions options;
    options.location.grazing_tolerance = 1e-12;
    const auto r =
        run(system, GetParam(), x0, LinearImpact::Mode::free, 0.0, t_end, 1e-13, 1e-13, options);
    SCOPED_TRACE("sigma = R (1 + " + std::to_string(relative) + ")");
    ASSERT_EQ(r.result.termination, Termination::completed);
    ++cases;
    if (relative > 0.0) {
      EXPECT_TRUE(r.events.empty()) << "spurious " << to_string(r.events.front().kind)
                                    << " at t = " << r.events.front().t;
      continue;
    }
    ASSERT_FALSE(r.events.empty()) << "missed impact";
    const double ratio = p.sigma / R;
    const double speed = R * p.omega * std::sqrt(1.0 - ratio * ratio);
    EXPECT_EQ(r.events[0].kind, EventKind::impact);
    // a shallow dip's crossing is ill-conditioned: a state error δx (about
    // 1e-13 here) moves it by δx / ẋ in time and the speed by δx ω² R / ẋ
    EXPECT_NEAR(r.events[0].t, first_time(std::acos(ratio)), 1e-10 + 1e-12 / speed);
    EXPECT_NEAR(r.events[0].qdot_before, speed, 1e-10 + 1e-12 / speed);
  }
  EXPECT_EQ(cases, 10);
}

// ---------------------------------------------------------------------------
// e_n = 1: the elastic, undamped, unforced linear oscillator from x = 0,
// ẋ = 1 with the stop at σ = 1/2. x = sin t meets the stop at π/6, is
// reflected, and every later flight is the sine's arc below σ: impacts at
// t_k = π/6 + k (π + 2 asin σ) = π/6 + 4πk/3, all with ẋ⁻ = cos(π/6). Over
// 200 impacts: none lost, no accumulation, and the times and speeds within
// the global error of a tolerance-controlled one-step method, which grows
// linearly in time (at rtol = 1e-12 by about 1e-11 per time unit; the bound
// allows 100 rtol per time unit, far below one impact interval).
TEST_P(HardCaseExactFlow, ElasticImpactsKeepTheirClosedFormTimes) {
  LinearImpactParameters p;
  p.zeta = 0.0;
  p.A = 0.0;
  p.sigma = 0.5;
  p.r = 1.0;
  const LinearImpact system(p);
  constexpr int count = 200;
  const double interval = 4.0 * pi / 3.0;
  const auto r = run(system, GetParam(), {0.0, 1.0}, LinearImpact::Mode::free, 0.0,
                     pi / 6.0 + (count - 0.5) * interval);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_EQ(r.events.size(), static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const EventRecord& e = r.events[static_cast<std::size_t>(k)];
    EXPECT_EQ(e.kind, EventKind::impact);
    const double t = pi / 6.0 + k * interval;
    EXPECT_NEAR(e.t, t, 1e-9 + 1e-10 * t) << "impact " << k;
    EXPECT_NEAR(e.qdot_before, std::cos(pi / 6.0), 1e-9 + 1e-10 * t) << "impact " << k;
    EXPECT_EQ(e.qdot_after, -e.qdot_before);
  }
}

// e_n = 0 on the ball: dropped from 5 cm onto the default table with r = 0,
// the ball stops relative to the table at the first impact (the closed-form
// meeting of the parabola and A sin ωt): the accumulation and the contact
// start are at that same instant, and it rides until the closed-form release.
TEST_P(HardCaseExactFlow, PlasticBallSticksAtItsFirstImpact) {
  BouncingBallParameters p;
  p.r = 0.0;
  const BouncingBall system(p);
  const double period = 2.0 * pi / p.omega;
  const auto r =
      run(system, GetParam(), {0.05, 0.0}, BouncingBall::Mode::free, 0.0, 2.0 * period);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_GE(r.events.size(), 4u);
  const double first =
      root_in([&](double t) { return 0.05 - 0.5 * p.g * t * t - p.A * std::sin(p.omega * t); },
              0.0, 0.2);
  EXPECT_EQ(r.events[0].kind, EventKind::impact);
  EXPECT_NEAR(r.events[0].t, first, 1e-10);
  EXPECT_NEAR(r.events[0].qdot_after, p.A * p.omega * std::cos(p.omega * r.events[0].t), 1e-12);
  EXPECT_EQ(r.events[1].kind, EventKind::accumulation);
  EXPECT_EQ(r.events[1].t, r.events[0].t);
  EXPECT_EQ(r.events[2].kind, EventKind::contact_start);
  EXPECT_EQ(r.events[3].kind, EventKind::contact_end);
  double release = std::asin(p.g / (p.A * p.omega * p.omega)) / p.omega;
  while (release < first) release += period;
  EXPECT_NEAR(r.events[3].t, release, 1e-9);
}

// e_n = 0 on the pendulum (V0 = 4.163): every impact leaves the bob at rest on
// the wall. Where the wall attracts (g_e = g − V0 ω cos ωt < 0) the impact is
// its own accumulation point: an accumulation at the same instant follows;
// where it repels, the bob leaves the wall with no accumulation.
TEST_P(HardCasePendulum, PlasticImpactsStickWhereTheWallAttracts) {
  PendulumWallsParameters p;
  p.V0 = 4.163;
  p.e_n = 0.0;
  const PendulumWalls system(p);
  const auto r = run(system, GetParam(), {0.0, 0.1, 0.0}, PendulumWalls::Mode::free, 0.0,
                     20.0 * 2.0 * pi / p.omega, 1e-10, 1e-12);
  ASSERT_EQ(r.result.termination, Termination::completed);
  std::size_t impacts = 0;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    const EventRecord& e = r.events[i];
    if (e.kind != EventKind::impact) continue;
    ++impacts;
    EXPECT_EQ(e.qdot_after, 0.0);
    const double g_e = p.g - p.V0 * p.omega * std::cos(p.omega * e.t);
    const bool follows = i + 1 < r.events.size() &&
                         r.events[i + 1].kind == EventKind::accumulation &&
                         r.events[i + 1].t == e.t;
    EXPECT_EQ(follows, g_e < 0.0) << "impact at t = " << e.t << ", g_e = " << g_e;
  }
  EXPECT_GE(impacts, 5u);
}

// ---------------------------------------------------------------------------
// Very small gaps: walls 2b = 20 µm apart (θ0 ≈ 1.4e-5 rad), no forcing, no
// damping, elastic. Energy fixes the speed at the walls,
// θ̇_w² = θ̇0² − 2 (g/l)(1 − cos θ0); the flight times come from the
// quadrature of dθ / θ̇(θ) (Gauss–Kronrod): first impact t1 from θ = 0 to
// θ0, then Δ between the walls. Over 1000 flights: the impacts alternate
// walls, none is lost or doubled (the count in [0, t1 + 999.5 Δ] is 1000),
// each at t1 + kΔ and with speed θ̇_w.
TEST_P(HardCasePendulum, WallsMicronsApartLoseNoImpact) {
  PendulumWallsParameters p;
  p.V0 = 0.0;
  p.d = 0.0;
  p.e_n = 1.0;
  p.b = 1e-5;
  const PendulumWalls system(p);
  const double theta0 = std::asin(p.b / p.l);
  const double rate0 = 1.0;  // rad/s at θ = 0
  auto speed = [&](double theta) {
    return std::sqrt(rate0 * rate0 - 2.0 * (p.g / p.l) * (1.0 - std::cos(theta)));
  };
  using Quadrature = boost::math::quadrature::gauss_kronrod<double, 31>;
  const double t1 = Quadrature::integrate([&](double th) { return 1.0 / speed(th); }, 0.0, theta0);
  const double delta =
      Quadrature::integrate([&](double th) { return 1.0 / speed(th); }, -theta0, theta0);
  constexpr int count = 1000;
  const auto r = run(system, GetParam(), {0.0, rate0, 0.0}, PendulumWalls::Mode::free, 0.0,
                     t1 + (count - 0.5) * delta, 1e-12, 1e-14);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_EQ(r.events.size(), static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const EventRecord& e = r.events[static_cast<std::size_t>(k)];
    ASSERT_EQ(e.kind, EventKind::impact);
    EXPECT_EQ(e.wall, k % 2 == 0 ? 1 : -1) << "impact " << k;
    EXPECT_NEAR(e.t, t1 + k * delta, 1e-12 + 1e-9 * t1) << "impact " << k;
    EXPECT_NEAR(std::fabs(e.qdot_before), speed(theta0), 1e-9) << "impact " << k;
  }
}

// ---------------------------------------------------------------------------
// High forcing frequency: the ball on a table at ω = 3000 rad/s (T ≈ 2.1 ms),
// Γ = Aω²/g and r as in the defaults, started just after an impact of its
// period-1 orbit: impact phase cos φ = gT(1 − r) / (2Aω(1 + r)), take-off
// speed gT/2, so it lands after exactly T at the same height. The orbit is
// stable, so every one of 2000 impacts is at t0 + kT with ẏ⁻ = −gT/2.
TEST_P(HardCaseExactFlow, HighFrequencyTableKeepsThePeriodOneOrbit) {
  BouncingBallParameters p;
  const double gamma = p.A * p.omega * p.omega / p.g;
  p.omega = 3000.0;
  p.A = gamma * p.g / (p.omega * p.omega);
  const BouncingBall system(p);
  const double period = 2.0 * pi / p.omega;
  const double phase = std::acos(p.g * period * (1.0 - p.r) / (2.0 * p.A * p.omega * (1.0 + p.r)));
  const double t0 = phase / p.omega;
  constexpr int count = 2000;
  const auto r = run(system, GetParam(), {p.A * std::sin(phase), 0.5 * p.g * period},
                     BouncingBall::Mode::free, t0, t0 + (count + 0.5) * period);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_EQ(r.events.size(), static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const EventRecord& e = r.events[static_cast<std::size_t>(k)];
    EXPECT_EQ(e.kind, EventKind::impact);
    EXPECT_NEAR(e.t, t0 + (k + 1) * period, 1e-12) << "impact " << k;
    EXPECT_NEAR(e.qdot_before, -0.5 * p.g * period, 1e-10) << "impact " << k;
  }
}

// ---------------------------------------------------------------------------
// μ at the Painlevé limit μ tan θ0 = 1 (D = cos θ0 − μ sin θ0 = 0 up to
// round-off) and just above it are inconsistent: the run stops with a
// painleve event at the first impact slipping downwards (γ_T > 0). Just below
// (μ tan θ0 = 1 − 1e-6, D ≈ 1e-6 cos θ0 above the margin 1e-9) it is
// consistent: the run completes and the impulses at downward-slip impacts are
// the closed form M Δθ̇ / (W_N − μ W_T), large but finite.
TEST_P(HardCasePendulum, PainleveLimitStopsAtAndAboveAndNotBelow) {
  PendulumWallsParameters p;
  const double sin0 = p.b / p.l;
  const double cos0 = std::sqrt(1.0 - sin0 * sin0);
  const double mu_limit = cos0 / sin0;
  const double t_end = 60.0 * 2.0 * pi / p.omega;
  for (double factor : {1.0, 1.0 + 1e-6}) {
    p.mu = mu_limit * factor;
    const auto r = run(PendulumWalls(p), GetParam(), {0.0, 0.1, 0.0}, PendulumWalls::Mode::free,
                       0.0, t_end, 1e-10, 1e-12);
    SCOPED_TRACE("mu tan theta0 = " + std::to_string(factor));
    ASSERT_EQ(r.result.termination, Termination::stopped_by_model);
    ASSERT_FALSE(r.events.empty());
    EXPECT_EQ(r.events.back().kind, EventKind::painleve);
    EXPECT_GT(r.events.back().tangential_velocity, 0.0);
    for (const auto& e : of_kind(r.events, EventKind::impact))
      EXPECT_LT(e.tangential_velocity, 0.0) << "t = " << e.t;
  }
  p.mu = mu_limit * (1.0 - 1e-6);
  const auto r = run(PendulumWalls(p), GetParam(), {0.0, 0.1, 0.0}, PendulumWalls::Mode::free,
                     0.0, t_end, 1e-10, 1e-12);
  ASSERT_EQ(r.result.termination, Termination::completed);
  std::size_t downward = 0;
  for (const auto& e : of_kind(r.events, EventKind::impact)) {
    if (!(e.tangential_velocity > 0.0)) continue;
    ++downward;
    const double w_n = -e.wall * p.l * cos0;
    const double w_t = -e.wall * p.l * sin0;
    const double impulse =
        p.m * p.l * p.l * (e.qdot_after - e.qdot_before) / (w_n - p.mu * w_t);
    EXPECT_TRUE(std::isfinite(e.normal_impulse));
    EXPECT_NEAR(e.normal_impulse, impulse, 1e-6 * std::fabs(impulse));
  }
  EXPECT_GT(downward, 0u);
}

// ---------------------------------------------------------------------------
// 10^6 impacts with no drift in the event count: the period-1 orbit of the
// default ball (one impact per table period T, stable), closed-form flights,
// started just after an impact and run to 10^6 + 1/2 periods later. Exactly
// 10^6 impacts and nothing else, and the final state is the orbit's apex
// (ẏ = 0, y = y0 + gT²/8). The time per impact over the run (no slowdown) is
// measured by `impactlab bench`.
TEST(HardCase, MillionImpactsKeepAnExactCount) {
  const BouncingBallParameters p;
  const BouncingBall system(p);
  const double period = 2.0 * pi / p.omega;
  const double phase = std::acos(p.g * period * (1.0 - p.r) / (2.0 * p.A * p.omega * (1.0 + p.r)));
  const double t0 = phase / p.omega;
  const BouncingBall::State x0{p.A * std::sin(phase), 0.5 * p.g * period};
  constexpr std::uint64_t count = 1000000;
  StepperSettings settings;
  settings.max_step = system.max_step();
  EventLog log(false);
  ExactFlowStepper<BouncingBall> stepper(settings);
  const auto result = simulate(system, stepper, x0, BouncingBall::Mode::free, t0,
                               t0 + (static_cast<double>(count) + 0.5) * period, LoopOptions{}, log);
  ASSERT_EQ(result.termination, Termination::completed);
  EXPECT_EQ(log.count(EventKind::impact), count);
  EXPECT_EQ(result.counters.events, count);
  EXPECT_NEAR(result.state[1], 0.0, 1e-9);
  EXPECT_NEAR(result.state[0], x0[0] + p.g * period * period / 8.0, 1e-10);
}

// ---------------------------------------------------------------------------
// Events at t0: the pendulum starting on its right wall moving into it is an
// impact at t0, applied once (θ̇⁺ = −e_n θ̇⁻), and the next event is the
// next real impact, later. It starts at ωt0 = π/2, where the wall repels
// (g_e = g > 0), so no accumulation follows.
TEST_P(HardCasePendulum, StartOnAWallMovingInIsOneImpactAtT0) {
  const PendulumWallsParameters p;
  const PendulumWalls system(p);
  const double t0 = 0.5 * pi / p.omega;
  const auto r = run(system, GetParam(), {system.wall_angle(), 0.5, 0.0},
                     PendulumWalls::Mode::free, t0, t0 + 2.0, 1e-10, 1e-12);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_GE(r.events.size(), 2u);
  EXPECT_EQ(r.events[0].kind, EventKind::impact);
  EXPECT_EQ(r.events[0].t, t0);
  EXPECT_EQ(r.events[0].wall, 1);
  EXPECT_EQ(r.events[0].qdot_before, 0.5);
  EXPECT_DOUBLE_EQ(r.events[0].qdot_after, -p.e_n * 0.5);
  EXPECT_EQ(r.events[1].kind, EventKind::impact);
  EXPECT_GT(r.events[1].t, t0 + 1e-3);
}

// The accumulation rule where the wall's attraction is momentarily constant:
// on the right wall at ωt0 = 0 with V0 = 1.5 m/s, g_e = g − V0 ω < 0 (the
// wall attracts) and its rate is 0, so a first-order test alone accepts the
// constant-acceleration estimate at once, with t_rem of several seconds
// (a jump over periods where the wall repels). Every accepted accumulation
// must lie within a stretch where g_e < 0 throughout, checked on a fine grid
// from the impact that triggered it.
TEST_P(HardCasePendulum, AccumulationNeverJumpsOverAStretchWhereTheWallRepels) {
  PendulumWallsParameters p;
  p.V0 = 1.5;
  const PendulumWalls system(p);
  // θ̇0 = 0.5 rad/s: the rebound escapes the weak attraction, no accumulation
  // is due; θ̇0 = 0.002 rad/s: the rebounds are small enough to accumulate
  // before the wall repels again (ωt = 0.365 rad)
  for (const double rate : {0.5, 0.002}) {
    const auto r = run(system, GetParam(), {system.wall_angle(), rate, 0.0},
                       PendulumWalls::Mode::free, 0.0, 20.0, 1e-10, 1e-12);
    int accumulations = 0;
    for (std::size_t i = 1; i < r.events.size(); ++i) {
      if (r.events[i].kind != EventKind::accumulation) continue;
      ++accumulations;
      const double from = r.events[i - 1].t, to = r.events[i].t;
      for (int k = 0; k <= 1000; ++k) {
        const double t = from + (to - from) * k / 1000.0;
        ASSERT_LT(p.g - p.V0 * p.omega * std::cos(p.omega * t), 0.0)
            << "θ̇0 = " << rate << ": accumulation at " << to << " s jumps over t = " << t;
      }
    }
    if (rate < 0.01) {
      EXPECT_GT(accumulations, 0);
    }
  }
}

// The ball resting on the table at t0 while the table pushes it (g + z̈ > 0
// at t0 = 0): the event at t0 is a zero-speed touch, its own accumulation
// point; it rides from t0 and is released at the closed-form time.
TEST_P(HardCaseExactFlow, BallRestingOnTheTableAtT0RidesFromT0) {
  const BouncingBallParameters p;
  const BouncingBall system(p);
  const auto r = run(system, GetParam(), {0.0, p.A * p.omega}, BouncingBall::Mode::free, 0.0,
                     2.0 * pi / p.omega);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_GE(r.events.size(), 4u);
  EXPECT_EQ(r.events[0].kind, EventKind::impact);
  EXPECT_EQ(r.events[0].t, 0.0);
  EXPECT_EQ(r.events[1].kind, EventKind::accumulation);
  EXPECT_EQ(r.events[1].t, 0.0);
  EXPECT_EQ(r.events[2].kind, EventKind::contact_start);
  EXPECT_EQ(r.events[3].kind, EventKind::contact_end);
  EXPECT_NEAR(r.events[3].t, std::asin(p.g / (p.A * p.omega * p.omega)) / p.omega, 1e-9);
}

// An impact exactly at the end time on the pendulum: unforced, undamped,
// from θ = 0 with θ̇ = 1 rad/s the bob reaches the right wall at
// t1 = ∫_0^θ0 dθ / θ̇(θ) (quadrature, energy conserved); with t_end = t1 the
// impact is logged once and applied (the run ends with θ̇ = −e_n θ̇_w).
TEST_P(HardCasePendulum, ImpactExactlyAtTheEndTimeIsLoggedOnce) {
  PendulumWallsParameters p;
  p.V0 = 0.0;
  p.d = 0.0;
  const PendulumWalls system(p);
  const double theta0 = system.wall_angle();
  auto speed = [&](double theta) {
    return std::sqrt(1.0 - 2.0 * (p.g / p.l) * (1.0 - std::cos(theta)));
  };
  const double t1 = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
      [&](double th) { return 1.0 / speed(th); }, 0.0, theta0);
  LoopOptions options;
  options.location.grazing_tolerance = 1e-10;
  const auto r = run(system, GetParam(), {0.0, 1.0, 0.0}, PendulumWalls::Mode::free, 0.0, t1,
                     1e-12, 1e-14, options);
  ASSERT_EQ(r.result.termination, Termination::completed);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, EventKind::impact);
  EXPECT_NEAR(r.events[0].t, t1, 1e-9);
  EXPECT_EQ(r.result.t, t1);
  EXPECT_NEAR(r.result.state[1], -p.e_n * speed(theta0), 1e-8);
}

// A chatter where its stop is about to let go: the linear impact oscillator
// (ζ = 0.05, A = 1, σ = 0.5, r = 0.5) released from the stop where the push
// A cos ωt − σ falls through zero, ω = 0.46319, 6e-5 below the onset of
// complete chatter (analysis/chatter_onset.hpp). Its chatter in the next
// interval of positive push follows the self-similar sequence that would
// accumulate where the push vanishes, then leaves it and accumulates 0.03
// before: its last hops, 1e-3 long and 1e-9 high, are far shorter than a
// step, the push under them falls by a tenth over each, so the
// accumulation estimate is refused and each is resolved. A hop that lands
// and is missed lets the mass through the stop. Every impact must be the
// long-double reference's (tests/support/linear_impact_chatter.hpp) to 1e-8
// in time and 1e-8 of its speed (plus the floor that the gap's round-off
// sets), down to speeds of 1e-5 at least; the mass
// accumulates, rests and is released at the next zero of the push, and is
// never past the stop by more than 1e-12.
struct StopClearance {
  double spacing, t0, sigma;
  long index = 0;
  double max_penetration = 0.0;
  [[nodiscard]] double next_time() const { return t0 + static_cast<double>(index) * spacing; }
  template <class S, class M>
  void observe(double, const S& x, M) {
    ++index;
    max_penetration = std::max(max_penetration, x[0] - sigma);
  }
};

TEST_P(HardCaseExactFlow, ChatterWhereTheStopLetsGoLosesNoHop) {
  testing::ChatterParameters reference;
  LinearImpactParameters p;
  p.zeta = static_cast<double>(reference.zeta);
  p.A = static_cast<double>(reference.amplitude);
  p.sigma = static_cast<double>(reference.sigma);
  p.r = static_cast<double>(reference.restitution);
  p.omega = 0.46319;
  const LinearImpact system(p);
  const auto chatter = testing::reference_chatter(reference, p.omega, 40, true);
  ASSERT_EQ(chatter.side, 1);
  // from the release's flight 0.1 s on
  const double t0 = static_cast<double>(chatter.release) + 0.1;
  const auto start = testing::ChatterFlight(reference, p.omega, chatter.release, reference.sigma, 0.0L)
                         .at(chatter.release + 0.1L);
  const double next_release = static_cast<double>(chatter.next_release);
  StopClearance clearance{1e-4, t0, p.sigma};
  const auto r = run(system, GetParam(), {static_cast<double>(start[0]), static_cast<double>(start[1])},
                     LinearImpact::Mode::free, t0, next_release + 1.0, 1e-12, 1e-12, LoopOptions{},
                     clearance);
  ASSERT_EQ(r.result.termination, Termination::completed);
  // each impact is timed to the error of the gap over its speed, ρ/v (ρ = 8
  // ulps of σ: the gap's round-off and, with bulirsch_stoer, up to 5 ulps
  // of integration error at rtol 1e-12), and a timing error δ changes the
  // later speeds by the push times δ: the speeds' floor in double precision
  const double gap_roundoff = 8.0 * (std::nextafter(p.sigma, 1.0) - p.sigma);
  double timing_floor = 0.0;
  std::size_t k = 0;
  for (; k < r.events.size() && r.events[k].kind == EventKind::impact; ++k) {
    ASSERT_LT(k, chatter.impacts.size());
    const auto& expected = chatter.impacts[k];
    const double speed = static_cast<double>(expected.speed);
    const double push = std::fabs(p.A * std::cos(p.omega * r.events[k].t) - p.sigma);
    EXPECT_NEAR(r.events[k].t, static_cast<double>(expected.t), 1e-8) << "impact " << k;
    EXPECT_NEAR(r.events[k].qdot_before, speed, 1e-8 * speed + 2.0 * push * timing_floor)
        << "impact " << k;
    timing_floor += gap_roundoff / speed;
  }
  ASSERT_GE(k, 1u);
  EXPECT_LT(r.events[k - 1].qdot_before, 1e-5);
  ASSERT_LT(k + 2, r.events.size());
  EXPECT_EQ(r.events[k].kind, EventKind::accumulation);
  EXPECT_LT(r.events[k].t, next_release);
  EXPECT_EQ(r.events[k + 1].kind, EventKind::contact_start);
  EXPECT_EQ(r.events[k + 2].kind, EventKind::contact_end);
  EXPECT_NEAR(r.events[k + 2].t, next_release, 1e-9);
  EXPECT_LT(clearance.max_penetration, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, HardCaseExactFlow, ::testing::ValuesIn(all_steppers),
                         [](const auto& info) { return info.param; });
INSTANTIATE_TEST_SUITE_P(Steppers, HardCasePendulum, ::testing::ValuesIn(numerical_steppers),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace impactlab
