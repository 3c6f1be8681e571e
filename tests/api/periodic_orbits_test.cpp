// Every periodic orbit of a period (api/periodic_job.hpp's find_periodic_orbits,
// api/system_jobs.hpp's periodic_orbits_of_scene, Newton shooting with
// deflation):
// * the bouncing ball's period-1 orbits of one impact per forcing period are
//   exactly the closed form's, each found once, and where the closed form has
//   none, none is found;
// * the linear impact oscillator across a fold of its period-1 branch (the
//   fold located by continuation): the pair on one side, one stable and one
//   unstable, none of it on the other;
// * deflation changes the outcome: without it many starts converge to an
//   orbit already found, with it each converged start finds a new one;
// * a fixed point of P² that is a period-1 orbit is reported with minimal
//   period 1, once.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/api/periodic_job.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/io/bad_input.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

// |a − b| on the section's (q, q̇)
double distance(const std::vector<double>& a, const std::vector<double>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

// The orbits found with one impact per forcing period and no contact phase.
std::vector<FoundPeriodicOrbit> one_impact_orbits(const PeriodicOrbitsResult& result) {
  std::vector<FoundPeriodicOrbit> found;
  for (const auto& orbit : result.orbits)
    if (orbit.minimal_period == 1 && orbit.impacts == 1 && orbit.contact_phases == 0)
      found.push_back(orbit);
  return found;
}

void expect_no_orbit_twice(const PeriodicOrbitsResult& result) {
  for (std::size_t i = 0; i < result.orbits.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GT(distance(result.orbits[i].state, result.orbits[j].state), 1e-6)
          << "orbits " << result.orbits[j].id << " and " << result.orbits[i].id;
}

// The bouncing ball's period-1 orbits with one impact per forcing period
// T = 2π/ω, in closed form. The ball leaves the table z = A sin ωt at the
// impact time tᵢ with speed v and lands on it one period later, where the
// table is back at z(tᵢ): v T − g T²/2 = 0, so v = gT/2 and it lands at
// v − gT = −gT/2. Newton's law on the relative velocity, ẏ⁺ − ż =
// −r (ẏ⁻ − ż), with ẏ⁺ = gT/2 and ẏ⁻ = −gT/2 gives (1 + r) ż(tᵢ) =
// (1 − r) gT/2, that is the impact phase φ = ωtᵢ solves
//     cos φ = (1 − r) g π / ((1 + r) A ω²),
// two phases ±arccos in [0, 2π) where the right side is inside (−1, 1), none
// where it is outside; an orbit also needs its flight to stay above the
// table. Its point on the section t ≡ 0 (mod T): the flight time since the
// impact τ = T − φ/ω, y = A sin φ + vτ − gτ²/2, ẏ = v − gτ.
struct BallParameters {
  double g, A, omega, r;
};

std::vector<std::vector<double>> closed_form_period_one(const BallParameters& p) {
  const double T = 2.0 * std::numbers::pi / p.omega;
  const double v = p.g * T / 2.0;
  const double cosine =
      (1.0 - p.r) * p.g * std::numbers::pi / ((1.0 + p.r) * p.A * p.omega * p.omega);
  std::vector<std::vector<double>> points;
  if (!(std::abs(cosine) < 1.0)) return points;
  for (const double phase :
       {std::acos(cosine), 2.0 * std::numbers::pi - std::acos(cosine)}) {
    // the flight stays above the table (checked at 1000 times inside it)
    bool above = true;
    for (int k = 1; k < 1000; ++k) {
      const double s = T * k / 1000.0;
      const double ball = p.A * std::sin(phase) + v * s - p.g * s * s / 2.0;
      above = above && ball > p.A * std::sin(phase + p.omega * s);
    }
    if (!above) continue;
    const double tau = T - phase / p.omega;
    points.push_back({p.A * std::sin(phase) + v * tau - p.g * tau * tau / 2.0, v - p.g * tau});
  }
  return points;
}

Scene bouncing_ball_at(double amplitude) {
  Scene scene = load_scene("bouncing_ball");
  scene.values["A"] = amplitude;
  return scene;
}

TEST(PeriodicOrbits, BouncingBallOneImpactOrbitsAreTheClosedFormsEachOnce) {
  const Scene scene = bouncing_ball_at(0.0112);
  const BallParameters p{scene.number("g"), scene.number("A"), scene.number("omega"),
                         scene.number("r")};
  const auto expected = closed_form_period_one(p);
  ASSERT_EQ(expected.size(), 2U) << "the closed form has two period-1 orbits at this amplitude";

  PeriodicJob job;
  job.all = true;
  job.period = "1";
  job.starts = 100;
  const PeriodicOrbitsJobResult found = find_periodic_orbits(scene, job);
  expect_no_orbit_twice(found.result);
  const auto one_impact = one_impact_orbits(found.result);
  ASSERT_EQ(one_impact.size(), expected.size());
  for (const auto& point : expected) {
    const auto match = std::count_if(one_impact.begin(), one_impact.end(), [&](const auto& o) {
      return distance(o.state, point) < 1e-8;
    });
    EXPECT_EQ(match, 1) << "closed form (" << point[0] << ", " << point[1] << ")";
  }
  // the two are a saddle and a node or focus: one stable, one not
  EXPECT_NE(one_impact[0].stable, one_impact[1].stable);
  EXPECT_EQ(found.result.count(StartOutcome::known_orbit), 0);
}

TEST(PeriodicOrbits, BouncingBallFindsNoOneImpactOrbitWhereTheClosedFormHasNone) {
  // a table amplitude at which cos φ above is beyond 1
  const Scene scene = bouncing_ball_at(0.003);
  const BallParameters p{scene.number("g"), scene.number("A"), scene.number("omega"),
                         scene.number("r")};
  ASSERT_TRUE(closed_form_period_one(p).empty());
  PeriodicOrbitsRequest request;
  request.period = 1;
  request.starts = 100;
  request.box = {{"initial.y", 0.004, 0.08}, {"initial.y_dot", -1.0, 1.0}};
  const PeriodicOrbitsResult result = periodic_orbits_of_scene(scene, request);
  ASSERT_TRUE(result.available);
  EXPECT_TRUE(one_impact_orbits(result).empty());
}

// The linear impact oscillator with its stop at σ = 0.5: continuation of the
// period-1 branch in ω finds a fold; just on the branch's side of it the pair
// that meets there, one stable and one not, just past it neither.
TEST(PeriodicOrbits, LinearImpactPairOnOneSideOfAFoldAndNoneOnTheOther) {
  Scene scene = load_scene("linear_impact");
  scene.values["sigma"] = 0.5;
  scene.values["initial.x"] = 0.2;
  ContinuationJob continuation;
  continuation.parameter = "omega";
  continuation.from = 1.6;
  continuation.to = 4.0;
  const ContinuationJobResult branch = continuation_of_scene(scene, continuation);
  ASSERT_FALSE(branch.branches.empty());
  const auto& points = branch.branches[0].result.points;
  const auto fold = std::find_if(points.begin(), points.end(), [](const BifurcationPoint& p) {
    return p.type == BifurcationType::fold && p.located;
  });
  ASSERT_NE(fold, points.end()) << "no fold on the period-1 branch";
  // the side of the fold its branch lies on: that of the branch's point nearest it
  const auto& curve = branch.branches[0].result.branch;
  const auto nearest =
      std::min_element(curve.begin(), curve.end(), [&](const auto& a, const auto& b) {
        return distance(a.state, fold->state) < distance(b.state, fold->state);
      });
  ASSERT_NE(nearest->parameter, fold->parameter);
  const double side = nearest->parameter < fold->parameter ? -1.0 : 1.0;
  const double offset = 0.003 * fold->parameter;

  const auto orbits_at = [&](double omega) {
    Scene at = scene;
    at.values["omega"] = omega;
    PeriodicOrbitsRequest request;
    request.period = 1;
    request.starts = 200;
    request.box = {{"initial.x", -4.0, 0.5}, {"initial.x_dot", -4.0, 4.0}};
    const PeriodicOrbitsResult result = periodic_orbits_of_scene(at, request);
    expect_no_orbit_twice(result);
    std::vector<FoundPeriodicOrbit> pair;
    for (const auto& orbit : one_impact_orbits(result))
      if (distance(orbit.state, fold->state) < 1.0) pair.push_back(orbit);
    return pair;
  };
  const auto inside = orbits_at(fold->parameter + side * offset);
  ASSERT_EQ(inside.size(), 2U);
  EXPECT_NE(inside[0].stable, inside[1].stable);
  // the unstable one leaves through the multiplier that crossed +1 at the fold
  const auto& unstable = inside[0].stable ? inside[1] : inside[0];
  EXPECT_GT(unstable.multipliers[0].real(), 1.0);
  EXPECT_EQ(unstable.multipliers[0].imag(), 0.0);
  EXPECT_TRUE(orbits_at(fold->parameter - side * offset).empty());
}

TEST(PeriodicOrbits, DeflationMakesEveryConvergedStartANewOrbit) {
  const Scene scene = bouncing_ball_at(0.0112);
  PeriodicOrbitsRequest request;
  request.period = 1;
  request.starts = 100;
  request.box = {{"initial.y", 0.02, 0.08}, {"initial.y_dot", -1.0, 1.0}};
  request.deflate = false;
  const PeriodicOrbitsResult plain = periodic_orbits_of_scene(scene, request);
  request.deflate = true;
  const PeriodicOrbitsResult deflated = periodic_orbits_of_scene(scene, request);
  // without deflation, the starts pile onto orbits already found
  EXPECT_GE(plain.count(StartOutcome::known_orbit), 5);
  EXPECT_GT(plain.count(StartOutcome::known_orbit), plain.count(StartOutcome::new_orbit));
  // with it, each start that converges finds an orbit not known before
  EXPECT_EQ(deflated.count(StartOutcome::known_orbit), 0);
  EXPECT_GE(deflated.count(StartOutcome::new_orbit), 2);
  expect_no_orbit_twice(deflated);
}

TEST(PeriodicOrbits, PeriodOneOrbitAmongPeriodTwoFixedPointsHasMinimalPeriodOne) {
  const Scene scene = bouncing_ball_at(0.0112);
  PeriodicJob job;
  job.all = true;
  job.starts = 100;
  job.period = "1";
  const auto period_one = find_periodic_orbits(scene, job);
  job.period = "2";
  const auto period_two = find_periodic_orbits(scene, job);
  expect_no_orbit_twice(period_two.result);
  // the stable one-impact period-1 orbit (the attractor) is a fixed point of P²
  const auto one_impact = one_impact_orbits(period_one.result);
  const auto stable = std::find_if(one_impact.begin(), one_impact.end(),
                                   [](const auto& o) { return o.stable; });
  ASSERT_NE(stable, one_impact.end());
  int found = 0;
  for (const auto& orbit : period_two.result.orbits)
    if (distance(orbit.state, stable->state) < 1e-8) {
      ++found;
      EXPECT_EQ(orbit.minimal_period, 1);
      EXPECT_EQ(orbit.impacts, 1U);
    }
  EXPECT_EQ(found, 1);
  for (const auto& orbit : period_two.result.orbits)
    EXPECT_TRUE(orbit.minimal_period == 1 || orbit.minimal_period == 2);
}

TEST(PeriodicOrbits, BadInputNamesTheOption) {
  const Scene scene = load_scene("linear_impact");
  PeriodicJob job;
  job.all = true;
  job.starts = 0;
  EXPECT_EQ(testing::bad_input_key([&] { find_periodic_orbits(scene, job); }), "starts");
  job.starts = 3;
  job.box = {"initial.x=1"};
  EXPECT_EQ(testing::bad_input_key([&] { find_periodic_orbits(scene, job); }), "box");
  job.box = {"sigma=0:0.1"};  // a parameter: the orbits are those of one system
  EXPECT_EQ(testing::bad_input_key([&] { find_periodic_orbits(scene, job); }), "box");
  job.box = {"initial.x=0:2"};  // beyond the stop at σ = 0.2
  EXPECT_EQ(testing::bad_input_key([&] { find_periodic_orbits(scene, job); }), "box");
  job.box = {};
  job.max_iterations = 1;  // no start converges in one Newton step
  try {
    find_periodic_orbits(scene, job);
    ADD_FAILURE() << "no BadInput";
  } catch (const BadInput& bad) {
    EXPECT_EQ(bad.key(), "starts");
    EXPECT_NE(std::string(bad.what()).find("no orbit of period 1 from 3 starts"),
              std::string::npos)
        << bad.what();
  }
}

}  // namespace
}  // namespace impactlab
