// Attractors found by sampling and followed across a parameter
// (analysis/attractor_following.hpp, analysis/initial_box.hpp), on records
// and point sets made here, so that each rule is checked where it decides:
// * the box's samples depend on (seed, value, sample, key) alone, lie in
//   their ranges, and are spread uniformly;
// * an attractor's cycle starts at its canonical point, its fraction is k/K
//   with the binomial error, and its smallest impact speed and mean exponent
//   are taken over its samples;
// * the relative Hausdorff distance tells an orbit from its mirror image;
// * ids persist along the parameter, a period doubling keeps its id, and
//   births, deaths, merges and splits are reported where they happen.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/attractor_following.hpp>
#include <impactlab/analysis/initial_box.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::AttractorChange;
using impactlab::AttractorsAtValue;
using impactlab::SampledAttractor;
using impactlab::SectionPointSet;
using impactlab::SweepRecord;

SweepRecord record_with_cycle(const SectionPointSet& points, int period, double impacts_per_period,
                              double min_impact_speed, double lyapunov) {
  SweepRecord record;
  record.result.termination = impactlab::SectionTermination::completed;
  for (const auto& p : points) record.result.points.push_back({0.0, p[0], p[1], 0});
  record.result.min_impact_speed = min_impact_speed;
  record.result.lyapunov = lyapunov;
  record.result.periods_recorded = static_cast<double>(points.size());
  record.classification.period = period;
  record.classification.impacts_per_period = impacts_per_period;
  return record;
}

TEST(InitialBox, SamplesDependOnTheirCountersAloneAndFillTheirRange) {
  const impactlab::BoxRange range{"initial.theta", -0.05, 0.05};
  // the same counters give the same value, any other counter another one
  const double value = impactlab::box_value(range, 7, 3, 11, 0);
  EXPECT_EQ(value, impactlab::box_value(range, 7, 3, 11, 0));
  for (const auto& [seed, point, sample, key] :
       {std::tuple{8, 3, 11, 0}, std::tuple{7, 4, 11, 0}, std::tuple{7, 3, 12, 0},
        std::tuple{7, 3, 11, 1}})
    EXPECT_NE(value, impactlab::box_value(range, seed, point, sample, key));
  // 10000 samples: inside the range, mean 1/2 and variance 1/12 of the unit
  // interval to within 5 standard errors
  const int n = 10000;
  double sum = 0.0, sum_squares = 0.0;
  for (int s = 0; s < n; ++s) {
    const double u = impactlab::box_uniform(1, 0, s, 0);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_squares += u * u;
    const double x = impactlab::box_value(range, 1, 0, s, 0);
    ASSERT_GE(x, -0.05);
    ASSERT_LE(x, 0.05);
  }
  const double mean = sum / n, variance = sum_squares / n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(variance, 1.0 / 12.0, 5.0 * std::sqrt(1.0 / 180.0 / n));
}

TEST(AttractorFollowing, AnAttractorIsDescribedOverItsSamples) {
  // a period-2 cycle {a, b} seen from b first, then from a; a period-1 orbit;
  // a sample on no periodic attractor
  const std::array<double, 2> a{-0.25, 2.0}, b{0.5, 1.0}, c{0.1, 0.1};
  const auto from_b = record_with_cycle({b, a, b, a, b, a, b}, 2, 1.5, 0.3, -0.5);
  const auto from_a = record_with_cycle({a, b, a, b, a, b}, 2, 1.5, 0.2, -0.25);
  const auto fixed = record_with_cycle({c, c, c, c}, 1, 1.0, 0.7, -1.0);
  const auto chaos = record_with_cycle({a, c, b, c}, 0, 1.0, 0.01, 0.1);
  const auto found =
      impactlab::attractors_at_value(4, 2.5, {&from_b, &fixed, &from_a, &chaos}, 1e-6);
  EXPECT_EQ(found.index, 4);
  EXPECT_EQ(found.value, 2.5);
  EXPECT_EQ(found.samples, 4);
  EXPECT_EQ(found.unclassified, 1);
  EXPECT_EQ(found.sample_attractor, (std::vector<int>{1, 2, 1, 0}));
  ASSERT_EQ(found.attractors.size(), 2u);
  const SampledAttractor& two = found.attractors[0];
  EXPECT_EQ(two.period, 2);
  EXPECT_EQ(two.impacts_per_cycle, 3);  // 1.5 impacts per period over 2 periods
  // the cycle from its canonical (lexicographically smallest) point, in time order
  EXPECT_EQ(two.cycle, (SectionPointSet{a, b}));
  EXPECT_EQ(two.point, a);
  EXPECT_EQ(two.samples, 2);
  EXPECT_EQ(two.fraction, 0.5);
  EXPECT_DOUBLE_EQ(two.fraction_error, std::sqrt(0.5 * 0.5 / 4.0));
  EXPECT_EQ(two.min_impact_speed, 0.2);  // the smaller of its samples' 0.3 and 0.2
  EXPECT_DOUBLE_EQ(two.lyapunov, -0.375);
  EXPECT_EQ(found.attractors[1].fraction, 0.25);
  EXPECT_TRUE(std::isnan(impactlab::fraction_error(0.5, 0)));
}

TEST(AttractorFollowing, AnOrbitAndItsMirrorImageAreFarApart) {
  const SectionPointSet orbit{{0.04, 0.3}, {0.06, -0.1}};
  const SectionPointSet mirror{{-0.04, -0.3}, {-0.06, 0.1}};
  const SectionPointSet moved{{0.041, 0.301}, {0.061, -0.099}};
  EXPECT_EQ(impactlab::point_set_distance(orbit, orbit), 0.0);
  // each point's nearest mirror point is the other point's image, (0.1, 0.2)
  // away, over 1 + the largest |x| = |(0.04, 0.3)|: well above the match
  // tolerance
  EXPECT_DOUBLE_EQ(impactlab::point_set_distance(orbit, mirror),
                   std::hypot(0.1, 0.2) / (1.0 + std::hypot(0.04, 0.3)));
  EXPECT_LT(impactlab::point_set_distance(orbit, moved), 2e-3);
  // symmetric, and a doubled point near a single one is near it
  EXPECT_EQ(impactlab::point_set_distance(orbit, mirror),
            impactlab::point_set_distance(mirror, orbit));
  EXPECT_LT(impactlab::point_set_distance({{0.0, 0.5}}, {{0.001, 0.5}, {-0.001, 0.5}}), 2e-3);
  EXPECT_TRUE(std::isinf(impactlab::point_set_distance({}, orbit)));
}

// a value's attractors from their cycles alone
AttractorsAtValue value_with(int index, const std::vector<SectionPointSet>& cycles) {
  AttractorsAtValue at;
  at.index = index;
  at.value = index;
  for (const auto& cycle : cycles) {
    SampledAttractor a;
    a.cycle = cycle;
    a.period = static_cast<int>(cycle.size());
    at.attractors.push_back(a);
  }
  return at;
}

std::vector<int> ids(const AttractorsAtValue& at) {
  std::vector<int> found;
  for (const auto& a : at.attractors) found.push_back(a.id);
  return found;
}

TEST(AttractorFollowing, IdsPersistWhileABirthAndADeathAreReported) {
  // an orbit A and its mirror M drift slowly; A doubles its period at value 2
  // (one point becomes two nearby ones); B is born at value 2 and gone at 3
  const SectionPointSet A0{{0.04, 0.3}}, M0{{-0.04, -0.3}};
  const SectionPointSet A1{{0.041, 0.301}}, M1{{-0.041, -0.301}};
  const SectionPointSet A2{{0.0405, 0.302}, {0.0415, 0.300}}, M2{{-0.042, -0.302}};
  const SectionPointSet A3{{0.0407, 0.303}, {0.0417, 0.301}}, M3{{-0.043, -0.303}};
  const SectionPointSet B{{1.0, 2.0}};
  std::vector<AttractorsAtValue> values = {value_with(0, {A0, M0}), value_with(1, {M1, A1}),
                                           value_with(2, {B, A2, M2}), value_with(3, {M3, A3})};
  const auto events = impactlab::follow_attractors(values, 0.05);
  EXPECT_EQ(ids(values[0]), (std::vector<int>{1, 2}));
  EXPECT_EQ(ids(values[1]), (std::vector<int>{2, 1}));     // by distance, not by order
  EXPECT_EQ(ids(values[2]), (std::vector<int>{3, 1, 2}));  // the doubled A keeps 1
  EXPECT_EQ(ids(values[3]), (std::vector<int>{2, 1}));
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].change, AttractorChange::appear);
  EXPECT_EQ(events[0].index, 2);
  EXPECT_EQ(events[0].attractor, 3);
  EXPECT_EQ(events[1].change, AttractorChange::vanish);
  EXPECT_EQ(events[1].index, 3);
  EXPECT_EQ(events[1].attractor, 3);
  EXPECT_EQ(impactlab::to_string(events[1].change), "vanish");
}

TEST(AttractorFollowing, AMergeAndASplitNameBothAttractors) {
  // two orbits at q = ±0.02 meet in one at 0 (both 0.02/1.02 from it: the
  // tie goes to the old value's first), which splits again unevenly
  const SectionPointSet right{{0.02, 0.0}}, left{{-0.02, 0.0}}, middle{{0.0, 0.0}};
  const SectionPointSet nearer{{-0.019, 0.0}}, farther{{0.021, 0.0}};
  std::vector<AttractorsAtValue> values = {value_with(0, {right, left}),
                                           value_with(1, {middle}),
                                           value_with(2, {nearer, farther})};
  const auto events = impactlab::follow_attractors(values, 0.05);
  EXPECT_EQ(ids(values[1]), (std::vector<int>{1}));
  EXPECT_EQ(ids(values[2]), (std::vector<int>{1, 3}));  // the nearer continues
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].change, AttractorChange::merge);
  EXPECT_EQ(events[0].index, 1);
  EXPECT_EQ(events[0].attractor, 2);
  EXPECT_EQ(events[0].other, 1);
  EXPECT_EQ(events[1].change, AttractorChange::split);
  EXPECT_EQ(events[1].index, 2);
  EXPECT_EQ(events[1].attractor, 3);
  EXPECT_EQ(events[1].other, 1);
  // beyond the tolerance nothing is matched: a death and a birth
  const SectionPointSet away{{0.2, 0.0}};
  std::vector<AttractorsAtValue> far = {value_with(0, {middle}), value_with(1, {away})};
  const auto jumps = impactlab::follow_attractors(far, 0.05);
  ASSERT_EQ(jumps.size(), 2u);
  EXPECT_EQ(jumps[0].change, AttractorChange::appear);
  EXPECT_EQ(jumps[1].change, AttractorChange::vanish);
}

}  // namespace
