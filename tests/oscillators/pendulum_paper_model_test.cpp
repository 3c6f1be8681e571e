// Tests of the pendulum's Model P, the paper's piecewise sliding impact (Jin,
// Hu & Bishop 2003; oscillators/pendulum_walls/sliding_impact.hpp), against
// values computed by hand (decimal arithmetic, 40 digits) and closed forms:
// * the instantaneous-impact test (Eqs. 25-26) and the sliding-impact
//   residual (Eqs. 21-22) on hand-computed cases;
// * a sliding impact: the bob held on the wall with λ_N ≥ 0, leaving where
//   g_e = 0 (Eq. 20) with θ̇ = −e_n θ̇0 and the tangential velocity of Eq. 23;
// * an impact exactly on the Eq. 26 condition is instantaneous, and a
//   perturbed one slides;
// * the e_t = −1 limit, where every impact is instantaneous and the motion is
//   Model N's, event for event.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include <impactlab/oscillators/pendulum_walls/sliding_impact.hpp>

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

constexpr double pi = std::numbers::pi;
const std::vector<std::string> numerical_steppers = {"dopri5", "rkf78", "bulirsch_stoer", "rk8pd",
                                                     "taylor"};

// b / l = 1/14 in the paper's scene: tan θ0 = 1/√195
constexpr double tan_theta0_by_hand = 0.07161148740394328805;

TEST(SlidingImpactConditions, InstantaneousImpactTestOnHandComputedCases) {
  // v_n = 1 m/s, e_n = 0.3, e_y = −0.1: Eq. 26 holds at
  // v_y0 = −(1 + e_n) tan θ0 v_n / (1 + e_y) = −1.3 / (0.9 √195)
  const double v_y_instantaneous = -0.10343881513902919385;
  EXPECT_NEAR(instantaneous_impact_residual(1.0, v_y_instantaneous, 0.3, -0.1, tan_theta0_by_hand),
              0.0, 1e-16);
  EXPECT_TRUE(is_instantaneous_impact(1.0, v_y_instantaneous, 0.3, -0.1, tan_theta0_by_hand));
  EXPECT_FALSE(
      is_instantaneous_impact(1.0, v_y_instantaneous * (1 + 1e-6), 0.3, -0.1, tan_theta0_by_hand));
  // no tangential velocity: the residual is (1 + e_n) tan θ0 v_n = 1.3/√195
  EXPECT_NEAR(instantaneous_impact_residual(1.0, 0.0, 0.3, -0.1, tan_theta0_by_hand),
              0.09309493362512627447, 1e-16);
  EXPECT_FALSE(is_instantaneous_impact(1.0, 0.0, 0.3, -0.1, tan_theta0_by_hand));
  // a ball moving down (v_y0 > 0) never meets Eq. 26 with v_n > 0 and e_y > −1
  EXPECT_FALSE(is_instantaneous_impact(1.0, 0.5, 0.3, -0.1, tan_theta0_by_hand));
  // e_y = 0 (a sticking impact in the paper's words): v_y0 = −1.3 tan θ0 v_n
  EXPECT_TRUE(
      is_instantaneous_impact(2.0, -2.0 * 0.09309493362512627447, 0.3, 0.0, tan_theta0_by_hand));
  // e_y = −1, "no tangential effects": always instantaneous
  EXPECT_TRUE(is_instantaneous_impact(1.0, 0.0, 0.3, -1.0, tan_theta0_by_hand));
  EXPECT_TRUE(is_instantaneous_impact(1.0, 3.0, 0.0, -1.0, tan_theta0_by_hand));
}

TEST(SlidingImpactConditions, SlidingResidualOnHandComputedCases) {
  // V0 = 4.163 m/s, ω = 7 rad/s: √(V0² − (g/ω)²) = 3.92002129575639849857
  const double slip_end = 3.92002129575639849857;
  EXPECT_NEAR(slip_end_velocity(4.163, 7.0, 9.81), slip_end, 1e-14);
  // Eq. 22 holds when e_y v_y0 = −√(V0² − (g/ω)²): v_y0 = 39.2002... for e_y = −0.1
  EXPECT_NEAR(sliding_condition_residual(4.163, 7.0, 9.81, -0.1, 10.0 * slip_end), 0.0, 1e-13);
  EXPECT_NEAR(sliding_condition_residual(4.163, 7.0, 9.81, -0.1, 1.0), slip_end - 0.1, 1e-14);
  // V0 ω < g: g_e never vanishes, there is no end of slip and no residual
  EXPECT_TRUE(std::isnan(sliding_condition_residual(1.0, 7.0, 9.81, -0.1, 1.0)));
  // at V0 ω = g exactly the slip ends with zero tangential velocity
  EXPECT_NEAR(slip_end_velocity(9.81 / 7.0, 7.0, 9.81), 0.0, 1e-7);
}

using State = PaperPendulumWalls::State;

struct PaperRun {
  RunResult<State, PendulumMode> result;
  EventLog log;
};

// Records, on a uniform grid, the worst violation of "held on the wall with
// λ_N ≥ 0" in contact modes.
class HeldOnWallSampler {
 public:
  HeldOnWallSampler(const PaperPendulumWalls& system, double t0, double spacing)
      : system_(system), next_(t0), spacing_(spacing) {}
  [[nodiscard]] double next_time() const { return next_; }
  void observe(double t, const State& x, PendulumMode mode) {
    next_ = t + spacing_;
    if (mode == PendulumMode::free) return;
    ++contact_samples;
    // λ_N ≥ 0 ⇔ g_e ≤ 0 (D > 0 in this scene)
    max_effective_gravity = std::max(max_effective_gravity, system_.effective_gravity(t));
    const double wall = mode == PendulumMode::contact_right ? 1.0 : -1.0;
    max_position_error = std::max(max_position_error, std::fabs(x[0] - wall * system_.wall_angle()));
    max_rate = std::max(max_rate, std::fabs(x[1]));
  }
  int contact_samples = 0;
  double max_effective_gravity = -INFINITY, max_position_error = 0.0, max_rate = 0.0;

 private:
  const PaperPendulumWalls& system_;
  double next_, spacing_;
};

template <class Observer = NoObserver>
PaperRun run_paper(const PendulumWallsParameters& p, std::string_view method, const State& x0,
                   double t0, double t_end, Observer&& observer = Observer{}) {
  const PaperPendulumWalls system(p);
  StepperSettings settings;
  settings.rtol = 1e-11;
  settings.atol = 1e-13;
  settings.max_step = system.max_step();
  PaperRun out;
  out.result = with_flow<PaperPendulumWalls>(method, settings, [&](auto& stepper) {
    return simulate(system, stepper, x0, PendulumMode::free, t0, t_end, LoopOptions{}, out.log,
                    std::forward<Observer>(observer));
  });
  return out;
}

class PaperModel : public ::testing::TestWithParam<std::string> {};

// The bob reaches the right wall at ωt0 = 2π − 0.5, where g_e < 0: the
// impact slides. By hand: it stays on the wall through the slip reversal at
// ωt = 2π and leaves at ωt_f = 2π + acos(g / (V0 ω)) with θ̇ = −e_n θ̇0.
TEST_P(PaperModel, SlidingImpactHoldsTheBobAndReleasesWithRestitution) {
  PendulumWallsParameters p;
  p.V0 = 4.163;
  const PaperPendulumWalls system(p);
  const double theta0 = std::asin(p.b / p.l);
  const double t0 = (2.0 * pi - 0.5) / p.omega;
  const double rate0 = 1.0;  // θ̇0 (rad/s), towards the right wall
  const double t_release = (2.0 * pi + std::acos(p.g / (p.V0 * p.omega))) / p.omega;
  const double t_reversal = 2.0 * pi / p.omega;

  HeldOnWallSampler sampler(system, t0, 1e-3);
  const auto run = run_paper(p, GetParam(), {theta0, rate0, 0.0, 0.0}, t0, t_release + 0.05,
                             sampler);
  const auto& events = run.log.records();
  ASSERT_GE(events.size(), 4u);
  EXPECT_EQ(events[0].kind, EventKind::impact);
  EXPECT_EQ(events[0].t, t0);
  EXPECT_EQ(events[0].wall, 1);
  EXPECT_EQ(events[0].qdot_after, 0.0);  // the normal velocity is taken up
  EXPECT_GT(events[0].normal_impulse, 0.0);
  EXPECT_EQ(events[1].kind, EventKind::contact_start);
  EXPECT_GT(events[1].normal_force, 0.0);
  EXPECT_EQ(events[2].kind, EventKind::slip_reversal);
  EXPECT_NEAR(events[2].t, t_reversal, 1e-9);
  const EventRecord& release = events[3];
  ASSERT_EQ(release.kind, EventKind::contact_end);
  EXPECT_NEAR(release.t, t_release, 1e-9);
  EXPECT_NEAR(system.effective_gravity(release.t), 0.0, 1e-7);  // Eq. 20
  EXPECT_NEAR(release.qdot_after, -p.e_n * rate0, 1e-15);
  // Eq. 21's left side: the slip ends at V0 sin ωt_f = √(V0² − (g/ω)²)
  EXPECT_NEAR(release.tangential_velocity, 3.92002129575639849857, 1e-8);
  // Eq. 23: v_yf = V0 sin ωt_f + e_n v_x0 tan θ0, v_x0 = l cos θ0 θ̇0
  const double v_x0 = p.l * std::cos(theta0) * rate0;
  const double v_yf = 3.92002129575639849857 + p.e_n * v_x0 * tan_theta0_by_hand;
  const State left{theta0, release.qdot_after, 0.0, 0.0};
  EXPECT_NEAR(system.tangential_velocity(left, release.t), v_yf, 1e-8);

  // held on the wall, at rest, with λ_N ≥ 0, the whole time
  EXPECT_GT(sampler.contact_samples, 100);
  EXPECT_LE(sampler.max_effective_gravity, 1e-9);
  EXPECT_LE(sampler.max_position_error, 1e-15);
  EXPECT_EQ(sampler.max_rate, 0.0);
  // after the release the bob moves away from the wall: no event in 0.05 s
  EXPECT_EQ(events.size(), 4u);
  EXPECT_LT(run.result.state[0], theta0);
}

// Where the wall cannot hold the bob (g_e > 0 at ωt0 = π), the sliding impact
// has no duration: Newton's instantaneous impact, θ̇⁺ = −e_n θ̇0.
TEST_P(PaperModel, NoSlidingWhereTheWallCannotHold) {
  PendulumWallsParameters p;
  p.V0 = 4.163;
  const double theta0 = std::asin(p.b / p.l);
  const double t0 = pi / p.omega;
  const auto run = run_paper(p, GetParam(), {theta0, 1.0, 0.0, 0.0}, t0, t0 + 0.05);
  const auto& events = run.log.records();
  ASSERT_GE(events.size(), 1u);
  EXPECT_EQ(events[0].kind, EventKind::impact);
  EXPECT_NEAR(events[0].qdot_after, -0.3, 1e-15);
  EXPECT_EQ(run.log.count(EventKind::contact_start), 0u);
}

// On the wall at ωt0 = 2π − 0.35 with V0 = 4 m/s, e_n = 0.3, e_y = −0.9,
// Eq. 26 reads θ̇0 l sin θ0 (e_n − e_y) + (1 + e_y) V0 sin ωt0 = 0, so
// θ̇0 = 0.1 · 4 · sin 0.35 / (0.05 · 1.2) = 2.28598692... rad/s (by hand).
TEST_P(PaperModel, ImpactOnTheInstantaneousConditionDoesNotSlide) {
  PendulumWallsParameters p;
  p.V0 = 4.0;
  p.e_t = -0.9;
  const double theta0 = std::asin(p.b / p.l);
  const double t0 = (2.0 * pi - 0.35) / p.omega;
  const double rate0 = 0.4 * std::sin(0.35) / 0.06;

  const auto exact = run_paper(p, GetParam(), {theta0, rate0, 0.0, 0.0}, t0, t0 + 1e-3);
  ASSERT_GE(exact.log.records().size(), 1u);
  EXPECT_EQ(exact.log.records()[0].kind, EventKind::impact);
  // Model P's extension of the impact's record: its Eq. 26 residual
  EXPECT_NEAR(PaperPendulumWalls(p).impact_residuals(exact.log.records()[0]).instantaneous, 0.0,
              1e-12);
  EXPECT_NEAR(exact.log.records()[0].qdot_after, -0.3 * rate0, 1e-14);
  for (const auto& e : exact.log.records()) {
    if (e.t == t0) {
      EXPECT_NE(e.kind, EventKind::contact_start);
    }
  }

  const auto perturbed =
      run_paper(p, GetParam(), {theta0, rate0 * (1 + 1e-6), 0.0, 0.0}, t0, t0 + 1e-3);
  ASSERT_GE(perturbed.log.records().size(), 2u);
  EXPECT_EQ(perturbed.log.records()[0].qdot_after, 0.0);
  EXPECT_EQ(perturbed.log.records()[1].kind, EventKind::contact_start);
  EXPECT_EQ(perturbed.log.records()[1].t, t0);
}

// e_y = −1: no tangential law, so every impact is instantaneous and Model P
// is Model N, event for event, chatter, contact phase and release included.
TEST_P(PaperModel, TangentialRestitutionMinusOneIsModelN) {
  PendulumWallsParameters p;
  p.V0 = 4.163;
  p.e_t = -1.0;
  const double t_end = 100.0 * 2.0 * pi / p.omega;
  const auto paper = run_paper(p, GetParam(), {0.0, 0.1, 0.0, 0.0}, 0.0, t_end);

  const PendulumWalls newton_system(p);
  StepperSettings settings;
  settings.rtol = 1e-11;
  settings.atol = 1e-13;
  settings.max_step = newton_system.max_step();
  EventLog newton_log;
  with_flow<PendulumWalls>(GetParam(), settings, [&](auto& stepper) {
    return simulate(newton_system, stepper, PendulumWalls::State{0.0, 0.1, 0.0}, PendulumMode::free,
                    0.0, t_end, LoopOptions{}, newton_log);
  });

  const auto& a = paper.log.records();
  const auto& b = newton_log.records();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(paper.log.count(EventKind::contact_start), 0u);  // the chatter's contact phases
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].kind, b[i].kind) << "event " << i;
    EXPECT_EQ(a[i].t, b[i].t) << "event " << i;
    EXPECT_EQ(a[i].qdot_after, b[i].qdot_after) << "event " << i;
    if (i > 0 && a[i].kind == EventKind::contact_start) {
      EXPECT_EQ(a[i - 1].kind, EventKind::accumulation) << "a sliding impact at " << a[i].t;
    }
  }
}

// jin2003's chattering case (V0 = 4.163 m/s) over 30 forcing periods, at
// the scene's tolerances (rtol 1e-12, atol and grazing tolerance 1e-14): 30
// contact phases, each through a slip reversal (a zero of V0 sin ωt). Late in
// the run (t ≈ 9 s) the slip at the step after a reversal is evaluated at the
// rounded event time, |V0 ω| ulp(t) ≈ 5e-14 m/s from zero: more than the
// grazing tolerance, on either side. The Taylor stepper once took that for a
// new crossing at its step's start and stopped with no_progress after 10000
// reversals at one instant. It completes with the event sequence of rkf78
// at rtol 1e-13. The Runge–Kutta scan had the same absolute test at a
// step's start: dopri5 at rtol 1e-12 found 10 of the 28 reversals twice, a
// few ulps apart (38 in all). Both now take a witness within 16 ulps of time
// of a zero as at that zero (integrate/event_location.hpp's
// witness_at_zero), and every stepper gives rkf78's event sequence.
TEST_P(PaperModel, ThirtyChatteringPeriodsThroughTheirSlipReversalsComplete) {
  PendulumWallsParameters p;
  p.V0 = 4.163;
  const PaperPendulumWalls system(p);
  const double t_end = 30.0 * 2.0 * pi / p.omega;
  const State x0{0.0, 0.1, 0.0, 0.0};
  auto run = [&](std::string_view method, double rtol, EventLog& log) {
    StepperSettings settings;
    settings.rtol = rtol;
    settings.atol = 1e-14;
    settings.max_step = system.max_step();
    LoopOptions options;
    options.location.grazing_tolerance = 1e-14;
    return with_flow<PaperPendulumWalls>(method, settings, [&](auto& stepper) {
      return simulate(system, stepper, x0, PendulumMode::free, 0.0, t_end, options, log);
    });
  };
  EventLog log, reference;
  const auto result = run(GetParam(), 1e-12, log);
  run("rkf78", 1e-13, reference);
  ASSERT_EQ(result.termination, Termination::completed);
  ASSERT_GE(reference.count(EventKind::slip_reversal), 20u);
  const auto& events = log.records();
  ASSERT_EQ(events.size(), reference.records().size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    ASSERT_EQ(events[i].kind, reference.records()[i].kind) << i;
    EXPECT_NEAR(events[i].t, reference.records()[i].t, 1e-7) << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Steppers, PaperModel, ::testing::ValuesIn(numerical_steppers),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace impactlab
