// The ball on a vibrating table against its closed-form flights: impact times
// and velocities of every stepper, convergence as the tolerance tightens, the
// exact flow itself, and chattering into a riding phase and release.
//
// The reference below is derived here, independently of BouncingBall's own
// exact_flow: each flight is the parabola y0 + v0 (t − t0) − g (t − t0)²/2, each
// impact the first root of its gap to the table A sin ωt on a fine grid that
// also brackets the gap's minima, refined by TOMS 748 to full precision, and
// Newton's law (ẏ − ż)⁺ = −r (ẏ − ż)⁻ restarts the next flight.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <boost/math/tools/roots.hpp>
#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/api/work_precision.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::BouncingBall;
using impactlab::BouncingBallParameters;
using impactlab::EventKind;
using impactlab::EventLog;
using impactlab::EventRecord;
using impactlab::LoopOptions;
using impactlab::StepperSettings;

struct ReferenceImpact {
  double t;            // impact time (s)
  double ydot_before;  // ẏ⁻ (m/s)
  double ydot_after;   // ẏ⁺ (m/s)
};

// One parabolic flight leaving height y0 (m) at t0 (s) with velocity v0 (m/s),
// and its gap to the table.
struct Flight {
  BouncingBallParameters p;
  double t0, y0, v0;

  [[nodiscard]] double gap(double t) const {
    const double tau = t - t0;
    return y0 + v0 * tau - 0.5 * p.g * tau * tau - p.A * std::sin(p.omega * t);
  }
  [[nodiscard]] double gap_rate(double t) const {
    return v0 - p.g * (t - t0) - p.A * p.omega * std::cos(p.omega * t);
  }
  [[nodiscard]] double velocity(double t) const { return v0 - p.g * (t - t0); }
};

// Stop bracketing when the interval is 1e-14 wide or a few ulps of t.
bool converged(double a, double b) {
  return std::fabs(b - a) <=
         std::max(1e-14, 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(b));
}

template <class F>
double refine(F&& f, double a, double b) {
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(f, a, b, converged, iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// The first time after the flight's start where its gap reaches zero. A grid
// of a 2000th of the table period finds sign changes; where the gap's rate
// changes sign from negative to positive between two samples, the minimum is
// located and checked, so a pair of roots between grid points is not missed;
// a hop off the table shorter than one grid step is caught at its maximum.
double first_contact(const Flight& flight, double horizon) {
  const double step = 2.0 * std::numbers::pi / flight.p.omega / 2000.0;
  auto gap = [&](double t) { return flight.gap(t); };
  auto gap_rate = [&](double t) { return flight.gap_rate(t); };
  double ta = flight.t0;
  double left = gap(ta);
  for (int i = 1; ta < flight.t0 + horizon; ++i) {
    const double tb = flight.t0 + i * step;
    const double right = gap(tb);
    if (right <= 0.0) {
      if (i == 1 && gap_rate(ta) > 0.0) return refine(gap, refine(gap_rate, ta, tb), tb);
      return refine(gap, ta, tb);
    }
    if (left > 0.0 && gap_rate(ta) < 0.0 && gap_rate(tb) > 0.0) {
      const double t_min = refine(gap_rate, ta, tb);
      if (gap(t_min) <= 0.0) return refine(gap, ta, t_min);
    }
    ta = tb;
    left = right;
  }
  ADD_FAILURE() << "no contact within the horizon after t = " << flight.t0;
  return INFINITY;
}

double table_position(const BouncingBallParameters& p, double t) {
  return p.A * std::sin(p.omega * t);
}
double table_velocity(const BouncingBallParameters& p, double t) {
  return p.A * p.omega * std::cos(p.omega * t);
}

// The impact ending `flight`, and the flight that Newton's law starts there.
ReferenceImpact next_impact(Flight& flight) {
  const double te = first_contact(flight, 10.0);
  const double before = flight.velocity(te);
  const double table_speed = table_velocity(flight.p, te);
  const double after = table_speed - flight.p.r * (before - table_speed);
  flight = {flight.p, te, table_position(flight.p, te), after};
  return {te, before, after};
}

std::vector<ReferenceImpact> reference_impacts(Flight flight, int count) {
  std::vector<ReferenceImpact> impacts;
  for (int i = 0; i < count; ++i) impacts.push_back(next_impact(flight));
  return impacts;
}

// Γ = Aω²/g ≈ 1.03 and r = 0.8: a stable period-1 orbit (one bounce per
// table period, written out so that the test does not move with the
// defaults). Its impact phase φ solves cos φ = gT(1 − r) / (2Aω(1 + r)),
// T = 2π/ω; the run starts 2 mm above the orbit's apex, half a period after
// an impact, and settles back onto it without ever sticking.
BouncingBallParameters periodic_case() {
  BouncingBallParameters p;
  p.g = 9.81;
  p.A = 0.0112;
  p.omega = 30.0;
  p.r = 0.8;
  return p;
}

Flight periodic_start(const BouncingBallParameters& p) {
  const double period = 2.0 * std::numbers::pi / p.omega;
  const double phase =
      std::acos(p.g * period * (1.0 - p.r) / (2.0 * p.A * p.omega * (1.0 + p.r)));
  const double apex = p.A * std::sin(phase) + p.g * period * period / 8.0;
  return {p, phase / p.omega + 0.5 * period, apex + 0.002, 0.0};
}

constexpr int compared_impacts = 50;

// Events of a run with rtol = atol = `tolerance` and the steps bounded by
// `max_step_multiple` times the system's largest step.
std::vector<EventRecord> simulate_events(const BouncingBall& system, std::string_view method,
                                         double tolerance, const Flight& start, double t_end,
                                         double max_step_multiple = 1.0) {
  StepperSettings settings;
  settings.rtol = tolerance;
  settings.atol = tolerance;
  settings.max_step = max_step_multiple * system.max_step();
  EventLog log;
  const LoopOptions options;
  const auto result = impactlab::with_flow<BouncingBall>(method, settings, [&](auto& stepper) {
    return impactlab::simulate(system, stepper, BouncingBall::State{start.y0, start.v0},
                               BouncingBall::Mode::free, start.t0, t_end, options, log);
  });
  EXPECT_EQ(result.termination, impactlab::Termination::completed);
  return log.records();
}

// a measured error as a test property, in the XML report
std::string scientific(double value) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(3) << value;
  return out.str();
}

struct ImpactErrors {
  double time = 0.0;      // max |t − t_ref| (s)
  double velocity = 0.0;  // max |ẏ − ẏ_ref| over ẏ⁻ and ẏ⁺ (m/s)
};

ImpactErrors impact_errors(std::string_view method, double tolerance,
                           double max_step_multiple = 1.0) {
  const BouncingBallParameters p = periodic_case();
  const Flight start = periodic_start(p);
  const auto reference = reference_impacts(start, compared_impacts);
  const double t_end = reference.back().t + 0.25 * 2.0 * std::numbers::pi / p.omega;
  const auto events =
      simulate_events(BouncingBall(p), method, tolerance, start, t_end, max_step_multiple);
  ImpactErrors errors;
  EXPECT_EQ(events.size(), reference.size());
  for (std::size_t i = 0; i < std::min(events.size(), reference.size()); ++i) {
    EXPECT_EQ(events[i].kind, EventKind::impact) << "event " << i;
    EXPECT_EQ(events[i].wall, -1);
    errors.time = std::max(errors.time, std::fabs(events[i].t - reference[i].t));
    errors.velocity = std::max({errors.velocity,
                                std::fabs(events[i].qdot_before - reference[i].ydot_before),
                                std::fabs(events[i].qdot_after - reference[i].ydot_after)});
  }
  return errors;
}

class BouncingBallAgainstClosedForm : public ::testing::TestWithParam<std::string_view> {};

TEST_P(BouncingBallAgainstClosedForm, FirstFiftyImpactsAgreeAtTightTolerance) {
  const bool exact = GetParam() == "exact";
  const ImpactErrors errors = impact_errors(GetParam(), 1e-13);
  RecordProperty("max_time_error", scientific(errors.time));
  RecordProperty("max_velocity_error", scientific(errors.velocity));
  EXPECT_LT(errors.time, exact ? 1e-11 : 1e-9);
  EXPECT_LT(errors.velocity, exact ? 1e-11 : 1e-9);
}

// The flights are parabolas, which every stepper here integrates exactly
// (each has order >= 2, dopri5's dense output included): whatever the
// tolerance and however long the steps, the impacts are found to round-off.
// This is the bouncing ball's form of the convergence check: the error does
// not grow as the tolerance is loosened, because only event location (which
// is to full precision) contributes.
TEST_P(BouncingBallAgainstClosedForm, FlightsAreExactAtAnyTolerance) {
  constexpr double quarter_period = 4.0;  // multiple of max_step()
  for (double tolerance : {1e-6, 1e-9, 1e-12}) {
    const ImpactErrors errors = impact_errors(GetParam(), tolerance, quarter_period);
    EXPECT_LT(errors.time, 1e-11) << "tolerance " << tolerance;
    EXPECT_LT(errors.velocity, 1e-11) << "tolerance " << tolerance;
  }
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, BouncingBallAgainstClosedForm,
                         ::testing::ValuesIn(impactlab::stepper_names),
                         [](const auto& info) { return std::string(info.param); });

// The bench's closed-form reference (api/work_precision.hpp: the
// oscillator's exact_flow with a root search of its own) against the
// independent flights above, impact by impact.
TEST(WorkPrecisionReference, ClosedFormImpactsMatchIndependentFlights) {
  const BouncingBallParameters p = periodic_case();
  const Flight start = periodic_start(p);
  const auto reference = reference_impacts(start, compared_impacts);
  const auto impacts = impactlab::closed_form_impacts(
      BouncingBall(p), BouncingBall::State{start.y0, start.v0}, BouncingBall::Mode::free,
      start.t0, reference.back().t + 0.1, compared_impacts);
  ASSERT_EQ(impacts.size(), reference.size());
  for (std::size_t i = 0; i < impacts.size(); ++i) {
    EXPECT_NEAR(impacts[i].t, reference[i].t, 1e-12) << "impact " << i;
    EXPECT_NEAR(impacts[i].qdot_before, reference[i].ydot_before, 1e-11) << "impact " << i;
  }
}

TEST(BouncingBallExactFlow, FreeFlightIsAParabola) {
  const BouncingBall system(periodic_case());
  const BouncingBall::State x0{0.3, 1.2};
  BouncingBall::State x;
  system.exact_flow(BouncingBall::Mode::free, x0, 1.0, 1.5, x);
  EXPECT_NEAR(x[0], 0.3 + 1.2 * 0.5 - 0.5 * 9.81 * 0.25, 1e-15);
  EXPECT_NEAR(x[1], 1.2 - 9.81 * 0.5, 1e-15);
}

TEST(BouncingBallExactFlow, RidingBallFollowsTheTable) {
  const BouncingBallParameters p = periodic_case();
  const BouncingBall system(p);
  const double t0 = 0.1;
  const BouncingBall::State x0{table_position(p, t0), table_velocity(p, t0)};
  for (double t : {0.1, 0.13, 0.2, 0.31}) {
    BouncingBall::State x;
    system.exact_flow(BouncingBall::Mode::stuck, x0, t0, t, x);
    EXPECT_NEAR(x[0], table_position(p, t), 1e-15) << "t = " << t;
    EXPECT_NEAR(x[1], table_velocity(p, t), 1e-14) << "t = " << t;
  }
}

// Dropped onto the table with r = 0.5, the ball chatters while the table
// pushes it (g + z̈ > 0), rides on the table from the accumulation point, is
// released where the table's acceleration falls through −g, at
// sin ωt = g / (Aω²) on the rising branch, and flies again.
class BouncingBallSticking : public ::testing::TestWithParam<std::string_view> {};

TEST_P(BouncingBallSticking, ChattersRidesOnTheTableAndIsReleased) {
  BouncingBallParameters p = periodic_case();
  p.r = 0.5;
  const BouncingBall system(p);
  const Flight drop{p, 0.0, 0.05, 0.0};
  const double period = 2.0 * std::numbers::pi / p.omega;
  const double first_release = std::asin(p.g / (p.A * p.omega * p.omega)) / p.omega;
  const auto events = simulate_events(system, GetParam(), 1e-12, drop, 1.5 * period);

  // the chattering impacts agree with the closed form
  std::size_t accumulation = 0;
  while (accumulation < events.size() && events[accumulation].kind == EventKind::impact)
    ++accumulation;
  ASSERT_GE(accumulation, 5u);
  ASSERT_GE(events.size(), accumulation + 4);
  Flight flight = drop;
  std::vector<ReferenceImpact> reference;
  for (std::size_t i = 0; i < accumulation; ++i) reference.push_back(next_impact(flight));
  for (std::size_t i = 0; i < accumulation; ++i) {
    EXPECT_NEAR(events[i].t, reference[i].t, 1e-9) << "impact " << i;
    EXPECT_NEAR(events[i].qdot_before, reference[i].ydot_before, 1e-9) << "impact " << i;
    EXPECT_NEAR(events[i].qdot_after, reference[i].ydot_after, 1e-9) << "impact " << i;
  }
  // the accumulation point: the reference's impacts continued until their
  // flights are short (1e-7 s), then the geometric tail of hops r h, r² h, ...
  // (the acceleration is constant over it); the model's estimate may differ
  // by the error bound it reports, and by the impacts' own error (1e-9 s)
  double t_limit = 0.0;
  for (double hop = INFINITY; hop > 1e-7;) {
    const double t_before = flight.t0;
    t_limit = next_impact(flight).t;
    hop = t_limit - t_before;
    if (hop <= 1e-7) t_limit += hop * p.r / (1.0 - p.r);
  }
  const EventRecord& acc = events[accumulation];
  const EventRecord& start = events[accumulation + 1];
  const EventRecord& end = events[accumulation + 2];
  const double jumped = acc.t - events[accumulation - 1].t;
  EXPECT_EQ(acc.kind, EventKind::accumulation);
  EXPECT_GT(jumped, 0.0);
  EXPECT_NEAR(acc.t, t_limit, acc.accumulation_error + 1e-9);
  EXPECT_LE(acc.accumulation_error, p.accumulation.time);
  // riding starts with the accumulation, on the table, while it pushes
  EXPECT_EQ(start.kind, EventKind::contact_start);
  EXPECT_EQ(start.t, acc.t);
  EXPECT_EQ(start.wall, -1);
  EXPECT_GT(p.g - p.A * p.omega * p.omega * std::sin(p.omega * start.t), 0.0);
  EXPECT_NEAR(start.q, table_position(p, start.t), 1e-15);
  EXPECT_NEAR(start.qdot_after, table_velocity(p, start.t), 1e-15);
  // release where g + z̈ falls through zero: the first such time after t = 0
  // is before the accumulation, so the release is a table period later
  ASSERT_LT(first_release, start.t);
  const double release = first_release + period;
  ASSERT_GT(release, start.t);
  EXPECT_EQ(end.kind, EventKind::contact_end);
  EXPECT_NEAR(end.t, release, 1e-9);
  EXPECT_NEAR(end.q, table_position(p, release), 1e-10);
  EXPECT_NEAR(end.qdot_after, table_velocity(p, release), 1e-9);
  // flight again: the next impact is the closed-form landing of the ball
  // leaving the table with the table's velocity at the release
  const EventRecord& landing = events[accumulation + 3];
  Flight after_release{p, release, table_position(p, release), table_velocity(p, release)};
  const ReferenceImpact expected = next_impact(after_release);
  EXPECT_EQ(landing.kind, EventKind::impact);
  EXPECT_GT(landing.t - release, 0.1 * period);
  EXPECT_NEAR(landing.t, expected.t, 1e-9);
  EXPECT_NEAR(landing.qdot_before, expected.ydot_before, 1e-9);
  EXPECT_NEAR(landing.qdot_after, expected.ydot_after, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(AllSteppers, BouncingBallSticking,
                         ::testing::ValuesIn(impactlab::stepper_names),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
