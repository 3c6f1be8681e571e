// The event loop's guarantees (simulate/simulator.hpp), checked across every
// stepper on motions whose events are known in closed form:
// * a grazing contact (a double root of the gap) inside one step is seen, a
//   pair of roots 1e-7 inside the stop is an impact, 1e-7 outside nothing;
// * an event exactly at t0 is applied once, before the first step;
// * an event exactly at the end time is logged once;
// * no event is found twice at the same instant;
// * a run whose time cannot advance, whose state overflows, whose end time or
//   restart time after an event is NaN, or that takes its whole step budget
//   stops with a termination naming that, never `completed`.
// The motions: LinearImpact with ζ = 0, A = 0 is the harmonic oscillator,
// x = x0 cos t + ẋ0 sin t between impacts.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::BouncingBall;
using impactlab::BouncingBallParameters;
using impactlab::EventKind;
using impactlab::EventLog;
using impactlab::EventRecord;
using impactlab::LinearImpact;
using impactlab::LinearImpactParameters;
using impactlab::LoopOptions;
using impactlab::StepperSettings;
using impactlab::Termination;
constexpr double pi = std::numbers::pi;

// the undamped, unforced oscillator ẍ + x = 0 with a stop at σ
LinearImpactParameters harmonic(double sigma) {
  LinearImpactParameters p;
  p.zeta = 0.0;
  p.A = 0.0;
  p.omega = 2.0;  // irrelevant with A = 0, away from the resonance ω = 1
  p.sigma = sigma;
  p.r = 0.8;
  return p;
}

template <class System>
struct Run {
  impactlab::RunResult<typename System::State, typename System::Mode> result;
  std::vector<EventRecord> events;
};

template <class System>
Run<System> run(const System& system, std::string_view method, const StepperSettings& settings,
                const LoopOptions& options, typename System::State x0, double t0, double t_end) {
  EventLog log;
  const auto result = impactlab::with_flow<System>(method, settings, [&](auto& stepper) {
    return impactlab::simulate(system, stepper, x0, System::Mode::free, t0, t_end, options, log);
  });
  return {result, log.records()};
}

StepperSettings tight(double max_step) {
  StepperSettings settings;
  settings.rtol = 1e-12;
  settings.atol = 1e-12;
  settings.max_step = max_step;
  return settings;
}

class EventLoop : public ::testing::TestWithParam<std::string_view> {};

// x = sin t touches x = 1 at t = π/2 with zero velocity: a double root of the
// gap 1 − x. With steps of up to 2 time units (the exact flow takes exactly
// 2: the touch lies inside its first step, both step ends well clear of the
// stop) it must still be seen. The grazing tolerance is set above the
// integrators' error at rtol = 1e-12, so that their touch is a touch.
TEST_P(EventLoop, GrazingDoubleRootInsideOneStepIsSeen) {
  const LinearImpact system(harmonic(1.0));
  LoopOptions options;
  options.location.grazing_tolerance = 1e-9;
  const auto r = run(system, GetParam(), tight(2.0), options, {0.0, 1.0}, 0.0, 3.0);
  ASSERT_EQ(r.events.size(), 1u);
  const EventRecord& touch = r.events[0];
  EXPECT_TRUE(touch.kind == EventKind::grazing || touch.kind == EventKind::impact)
      << to_string(touch.kind);
  EXPECT_NEAR(touch.t, pi / 2.0, 1e-4);
  EXPECT_NEAR(touch.q, 1.0, 1e-9);
  EXPECT_NEAR(touch.qdot_before, 0.0, 1e-4);
  if (GetParam() == "exact") {
    EXPECT_EQ(touch.kind, EventKind::grazing);
  }
  EXPECT_EQ(r.result.termination, Termination::completed);
  EXPECT_EQ(r.result.t, 3.0);
}

// σ = 1 − 1e-7: two roots 2√(2e-7) ≈ 9e-4 apart around π/2, the gap positive
// at both ends of the step: the first root is an impact at asin σ with
// ẋ⁻ = √(1 − σ²).
TEST_P(EventLoop, PairOfRootsInsideOneStepIsAnImpact) {
  const double sigma = 1.0 - 1e-7;
  const LinearImpact system(harmonic(sigma));
  LoopOptions options;
  options.location.grazing_tolerance = 1e-9;
  const auto r = run(system, GetParam(), tight(2.0), options, {0.0, 1.0}, 0.0, 3.0);
  ASSERT_EQ(r.events.size(), 1u);
  const EventRecord& impact = r.events[0];
  const double speed = std::sqrt(1.0 - sigma * sigma);
  EXPECT_EQ(impact.kind, EventKind::impact);
  EXPECT_NEAR(impact.t, std::asin(sigma), 1e-7);
  EXPECT_NEAR(impact.qdot_before, speed, 1e-3 * speed);
  EXPECT_NEAR(impact.qdot_after, -0.8 * speed, 1e-3 * speed);
}

// σ = 1 + 1e-7: the orbit passes 1e-7 short of the stop: no event, and the
// run ends on the free motion x = sin t.
TEST_P(EventLoop, NearMissIsNoEvent) {
  const LinearImpact system(harmonic(1.0 + 1e-7));
  LoopOptions options;
  options.location.grazing_tolerance = 1e-9;
  const auto r = run(system, GetParam(), tight(2.0), options, {0.0, 1.0}, 0.0, 3.0);
  EXPECT_TRUE(r.events.empty());
  EXPECT_NEAR(r.result.state[0], std::sin(3.0), 1e-9);
  EXPECT_NEAR(r.result.state[1], std::cos(3.0), 1e-9);
}

// Starting on the stop (x0 = σ = 0.5) and moving into it (ẋ0 = 1): the impact
// at t0 is applied once, ẋ⁺ = −0.8. The motion after it is
// x = 0.5 cos t − 0.8 sin t = R cos(t + φ), tan φ = 0.8 / 0.5, back at the
// stop at t = 2π − 2φ.
TEST_P(EventLoop, EventAtStartIsAppliedOnce) {
  const LinearImpact system(harmonic(0.5));
  const double phi = std::atan2(0.8, 0.5);
  const double second = 2.0 * pi - 2.0 * phi;
  const auto r = run(system, GetParam(), tight(system.max_step()), LoopOptions{}, {0.5, 1.0},
                     0.0, second + 0.1);
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.events[0].kind, EventKind::impact);
  EXPECT_EQ(r.events[0].t, 0.0);
  EXPECT_EQ(r.events[0].qdot_before, 1.0);
  EXPECT_DOUBLE_EQ(r.events[0].qdot_after, -0.8);
  EXPECT_EQ(r.events[1].kind, EventKind::impact);
  EXPECT_NEAR(r.events[1].t, second, 1e-9);
  // x = R cos(t + φ) arrives with ẋ = R sin φ = 0.8
  EXPECT_NEAR(r.events[1].qdot_before, 0.8, 1e-9);
}

// x = sin t reaches σ = 0.5 at t = π/6; with t_end = π/6 the impact is at the
// end time: logged once, and applied (the run ends with ẋ⁺ = −0.8 cos(π/6)).
// The end-time check accepts a gap within the grazing tolerance, set above
// the integrators' error at rtol = 1e-12.
TEST_P(EventLoop, EventAtEndTimeIsLoggedOnce) {
  const LinearImpact system(harmonic(0.5));
  const double t_end = pi / 6.0;
  LoopOptions options;
  options.location.grazing_tolerance = 1e-10;
  const auto r =
      run(system, GetParam(), tight(system.max_step()), options, {0.0, 1.0}, 0.0, t_end);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, EventKind::impact);
  EXPECT_NEAR(r.events[0].t, t_end, 1e-9);
  EXPECT_NEAR(r.events[0].qdot_before, std::cos(t_end), 1e-9);
  EXPECT_EQ(r.result.t, t_end);
  EXPECT_NEAR(r.result.state[1], -0.8 * std::cos(t_end), 1e-9);
}

// Consecutive events are apart in time; only an accumulation and the contact
// start it opens share their instant. "Apart" is more than 1e-9: far below
// any real interval between two events of these runs (the shortest, the last
// chattering flights before an accumulation is accepted, are ~1e-5), far
// above the integrators' error in an event time, so the same event found
// twice from two slightly different states counts as repeated.
void expect_no_repeated_instant(const std::vector<EventRecord>& events) {
  constexpr double same_instant = 1e-9;
  for (std::size_t i = 1; i < events.size(); ++i) {
    const bool pair = events[i - 1].kind == EventKind::accumulation &&
                      events[i].kind == EventKind::contact_start;
    if (pair)
      EXPECT_EQ(events[i].t, events[i - 1].t) << "event " << i;
    else
      EXPECT_GT(events[i].t - events[i - 1].t, same_instant)
          << "event " << i << " at t = " << events[i].t << ": " << to_string(events[i - 1].kind)
          << " then " << to_string(events[i].kind);
  }
}

TEST_P(EventLoop, NoEventTwiceAtTheSameInstant) {
  // grazing every period: x = sin t touching σ = 1 at π/2 + 2πk, four times
  {
    const LinearImpact system(harmonic(1.0));
    LoopOptions options;
    options.location.grazing_tolerance = 1e-9;
    const auto r = run(system, GetParam(), tight(system.max_step()), options, {0.0, 1.0}, 0.0,
                       4.0 * 2.0 * pi);
    EXPECT_EQ(r.events.size(), 4u);
    expect_no_repeated_instant(r.events);
  }
  // the periodic impacting linear oscillator
  {
    LinearImpactParameters p;
    p.zeta = 0.05;
    p.A = 1.0;
    p.omega = 2.0;
    p.sigma = 0.2;
    p.r = 0.8;
    const LinearImpact system(p);
    const auto r = run(system, GetParam(), tight(system.max_step()), LoopOptions{}, {0.0, 0.0},
                       0.0, 100.0);
    EXPECT_GE(r.events.size(), 30u);
    expect_no_repeated_instant(r.events);
  }
  // chattering, riding on the table and release, three table periods
  {
    BouncingBallParameters p;
    p.A = 0.0112;
    p.omega = 30.0;
    p.r = 0.5;
    const BouncingBall system(p);
    const auto r = run(system, GetParam(), tight(system.max_step()), LoopOptions{}, {0.05, 0.0},
                       0.0, 3.0 * 2.0 * pi / p.omega);
    const auto riding = std::count_if(r.events.begin(), r.events.end(), [](const auto& e) {
      return e.kind == EventKind::contact_start;
    });
    EXPECT_GE(riding, 2);
    expect_no_repeated_instant(r.events);
  }
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, EventLoop, ::testing::ValuesIn(impactlab::stepper_names),
                         [](const auto& info) { return std::string(info.param); });

// A ball bouncing on a fixed floor under gravity, with restitution and no
// accumulation handling at all: its impacts accumulate at a finite time
// (Zeno). The loop must stop on its own with no_progress there, not hang and
// not let the ball through the floor.
class ZenoBall {
 public:
  using State = std::array<double, 2>;  // {height (m), velocity (m/s)}
  enum class Mode { free };
  static constexpr std::size_t max_witnesses = 1;
  static constexpr double gravity = 9.81;       // m/s²
  static constexpr double restitution = 0.5;

  template <class Number>
  void rhs(Mode, const std::array<Number, 2>& x, std::array<Number, 2>& dxdt,
           const Number&) const {
    dxdt[0] = x[1];
    dxdt[1] = -gravity;
  }
  [[nodiscard]] std::size_t witness_count(Mode) const { return 1; }
  [[nodiscard]] impactlab::TriggerDirection trigger_direction(Mode, std::size_t) const {
    return impactlab::TriggerDirection::falling;
  }
  template <class Number>
  [[nodiscard]] impactlab::BasicWitnessSample<Number> witness(
      Mode, std::size_t, const std::array<Number, 2>& x, const Number&) const {
    return {x[0], x[1]};
  }
  impactlab::Transition<State, Mode> on_event(Mode, std::size_t, impactlab::CrossingKind,
                                              const State& x, double t, EventLog& log) const {
    log.record({t, EventKind::impact, -1, x[0], x[1], -restitution * x[1]});
    return {{0.0, -restitution * x[1]}, Mode::free, t, false};
  }
  [[nodiscard]] double max_step() const { return 0.05; }
};

TEST_P(EventLoop, UnresolvedZenoStopsWithNoProgress) {
  if (GetParam() == "exact") GTEST_SKIP() << "ZenoBall has no closed-form flow here";
  const ZenoBall ball;
  // dropped from 1 m: first impact at √(2/g), then flights 2 r^k v1 / g
  const double v1 = std::sqrt(2.0 * ZenoBall::gravity);
  const double accumulation = v1 / ZenoBall::gravity +
                              2.0 * ZenoBall::restitution * v1 /
                                  (ZenoBall::gravity * (1.0 - ZenoBall::restitution));
  StepperSettings settings;
  settings.rtol = settings.atol = 1e-12;
  settings.max_step = ball.max_step();
  EventLog log;
  const auto result = impactlab::with_stepper<ZenoBall>(GetParam(), settings, [&](auto& stepper) {
    return impactlab::simulate(ball, stepper, ZenoBall::State{1.0, 0.0}, ZenoBall::Mode::free,
                               0.0, 2.0 * accumulation, LoopOptions{}, log);
  });
  EXPECT_EQ(result.termination, Termination::no_progress);
  EXPECT_NEAR(result.t, accumulation, 1e-6);
  // the ball never got through the floor by more than the tolerance
  EXPECT_GE(result.state[0], -1e-9);
  for (const EventRecord& e : log.records()) EXPECT_LE(e.t, accumulation + 1e-6);
}

// The ball whose impact asks to restart at a time that is not a number (as an
// accumulation's end computed from extreme parameters once did): the run
// stops at the impact with non_finite_state. It used to take the NaN as its
// time, leave the loop and report `completed`.
class NanRestartBall : public ZenoBall {
 public:
  impactlab::Transition<State, Mode> on_event(Mode mode, std::size_t k, impactlab::CrossingKind kind,
                                              const State& x, double t, EventLog& log) const {
    auto transition = ZenoBall::on_event(mode, k, kind, x, t, log);
    transition.time = NAN;
    return transition;
  }
};

TEST_P(EventLoop, NanRestartTimeStopsTheRun) {
  if (GetParam() == "exact") GTEST_SKIP() << "the ball has no closed-form flow here";
  const NanRestartBall ball;
  StepperSettings settings;
  settings.rtol = settings.atol = 1e-12;
  settings.max_step = ball.max_step();
  EventLog log;
  const auto result = impactlab::with_stepper<NanRestartBall>(GetParam(), settings, [&](auto& stepper) {
    return impactlab::simulate(ball, stepper, ZenoBall::State{1.0, 0.0}, ZenoBall::Mode::free, 0.0,
                               2.0, LoopOptions{}, log);
  });
  const double first_impact = std::sqrt(2.0 / ZenoBall::gravity);  // s, dropped from 1 m
  EXPECT_EQ(result.termination, Termination::non_finite_state) << to_string(result.termination);
  EXPECT_NEAR(result.t, first_impact, 1e-8);
  EXPECT_TRUE(std::isfinite(result.state[0]) && std::isfinite(result.state[1]));
  EXPECT_EQ(log.records().size(), 1u);
}

// At t0 = 1e17 s the spacing of doubles is 16 s, so that t + step
// == t for any step of this oscillator (max step 0.5): the run must say so,
// not report `completed` with the initial state (it did, with five identical
// section points).
TEST_P(EventLoop, FrozenTimeStopsTheRun) {
  const LinearImpact system(harmonic(2.0));
  const double t0 = 1e17;
  LoopOptions options;
  const auto run_result = run(system, GetParam(), tight(0.5), options, {0.5, 0.0}, t0, t0 + 100.0);
  EXPECT_EQ(run_result.result.termination, Termination::frozen_time);
  EXPECT_EQ(run_result.result.t, t0);
}

// x = x0 cos t + v0 sin t from x0 = v0 = -1.5e308 reaches -2.1e308 at t = π/4,
// past the largest double, away from the stop: the run stops (non_finite_state,
// or integrator_failure where the stepper's own error control gives up first)
// at a finite state, never `completed`.
TEST_P(EventLoop, OverflowingStateStopsTheRun) {
  const LinearImpact system(harmonic(2.0));
  LoopOptions options;
  const auto run_result =
      run(system, GetParam(), tight(0.1), options, {-1.5e308, -1.5e308}, 0.0, 10.0);
  EXPECT_TRUE(run_result.result.termination == Termination::non_finite_state ||
              run_result.result.termination == Termination::integrator_failure)
      << to_string(run_result.result.termination);
  EXPECT_LT(run_result.result.t, 10.0);
  EXPECT_TRUE(std::isfinite(run_result.result.state[0]) && std::isfinite(run_result.result.state[1]));
}

// A NaN end time (from a NaN phase: `periodic --phase nan` reported an orbit
// "converged after 0 iterations") is not a run that completed.
TEST_P(EventLoop, NanEndTimeIsNotCompleted) {
  const LinearImpact system(harmonic(2.0));
  LoopOptions options;
  const auto run_result = run(system, GetParam(), tight(0.5), options, {0.5, 0.0}, 0.0, NAN);
  EXPECT_EQ(run_result.result.termination, Termination::non_finite_state);
}

// Every run is bounded: past its step budget it stops, having taken exactly
// that many steps.
TEST_P(EventLoop, StepBudgetStopsTheRun) {
  const LinearImpact system(harmonic(2.0));
  LoopOptions options;
  options.step_budget = 25;
  const auto run_result = run(system, GetParam(), tight(0.5), options, {0.5, 0.0}, 0.0, 1e6);
  EXPECT_EQ(run_result.result.termination, Termination::step_budget);
  EXPECT_EQ(run_result.result.counters.steps, 25u);
  EXPECT_LT(run_result.result.t, 1e6);
}

}  // namespace
