// The scan of one step for events (integrate/event_location.hpp), compiled
// once for every system, on witnesses given in closed form: crossings in
// either trigger direction located to a few ulps of the exact root, a
// minimum within the grazing tolerance taken for a grazing and one just
// above it for nothing, a dip below zero bracketed before its minimum, a
// violation reported as unresolved, the earliest of several witnesses, and a
// cheap interpolant that is wrong by far more than the tolerance but never
// moves or hides an event.
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/integrate/event_location.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

// A witness in closed form: its value and rate at t.
struct ClosedForm {
  TriggerDirection direction;
  std::function<double(double)> value;
  std::function<double(double)> rate;
};

// The witnesses on the exact flow; `scan_error` is added to every value
// the cheap interpolant gives (and nothing else).
class ClosedFormWitnesses final : public StepWitnesses {
 public:
  ClosedFormWitnesses(std::vector<ClosedForm> witnesses, const ScanSamples& samples,
                      double scan_error = 0.0)
      : witnesses_(std::move(witnesses)), samples_(samples), scan_error_(scan_error) {}

  [[nodiscard]] std::size_t count() const override { return witnesses_.size(); }
  [[nodiscard]] TriggerDirection direction(std::size_t k) const override {
    return witnesses_[k].direction;
  }
  [[nodiscard]] WitnessSample on_sample(std::size_t k, int i) const override {
    const double t = samples_.times[i];
    const bool interior = i > 0 && i < samples_.n;
    return {witnesses_[k].value(t) + (interior ? scan_error_ : 0.0), witnesses_[k].rate(t)};
  }
  [[nodiscard]] WitnessSample on_state_at(std::size_t k, double t) const override {
    return {witnesses_[k].value(t), witnesses_[k].rate(t)};
  }
  [[nodiscard]] WitnessSample on_scan_at(std::size_t k, double t) const override {
    return {witnesses_[k].value(t) + scan_error_, witnesses_[k].rate(t)};
  }

 private:
  std::vector<ClosedForm> witnesses_;
  const ScanSamples& samples_;
  double scan_error_;
};

// g(t) = (t − c)² + m: a minimum m at c
ClosedForm parabola(double c, double m) {
  return {TriggerDirection::falling, [=](double t) { return (t - c) * (t - c) + m; },
          [=](double t) { return 2.0 * (t - c); }};
}

LocatedEvent locate(std::vector<ClosedForm> witnesses, double ta, double tb,
                    bool cheap_scan = false, double scan_error = 0.0) {
  const EventLocationOptions options;  // grazing tolerance 1e-12, no max_step
  const ScanSamples samples(ta, tb, options);
  const ClosedFormWitnesses view(std::move(witnesses), samples, scan_error);
  return locate_first_event(view, samples, cheap_scan, options, static_cast<std::size_t>(-1));
}

// within n ulps of the exact time
void expect_near_ulps(double located, double exact, double n) {
  EXPECT_LE(std::fabs(located - exact), n * std::numeric_limits<double>::epsilon() * exact)
      << "located " << located << " against " << exact;
}

TEST(EventLocation, SamplesSpanTheStepInAtMostSixteenIntervals) {
  EventLocationOptions options;
  const ScanSamples unbounded(2.0, 3.0, options);  // no max_step: the most intervals
  EXPECT_EQ(unbounded.n, ScanSamples::max_intervals);
  EXPECT_EQ(unbounded.times[0], 2.0);
  EXPECT_EQ(unbounded.times[unbounded.n], 3.0);
  options.max_step = 1.0;  // intervals no longer than 1/4
  const ScanSamples bounded(2.0, 3.1, options);
  EXPECT_EQ(bounded.n, 5);
  for (int i = 0; i < bounded.n; ++i) EXPECT_LE(bounded.times[i + 1] - bounded.times[i], 0.25);
  const ScanSamples short_step(2.0, 2.01, options);
  EXPECT_EQ(short_step.n, 1);
}

TEST(EventLocation, FallingCrossingToAFewUlpsOfTheRoot) {
  // 1 − t² falls through zero at t = 1
  const LocatedEvent event = locate(
      {{TriggerDirection::falling, [](double t) { return 1.0 - t * t; },
        [](double t) { return -2.0 * t; }}},
      0.0, 2.0);
  ASSERT_TRUE(event.found);
  EXPECT_EQ(event.kind, CrossingKind::crossing);
  EXPECT_EQ(event.witness, 0u);
  expect_near_ulps(event.t, 1.0, 4);
}

TEST(EventLocation, RisingCrossingIsTheNegatedWitnessFalling) {
  const double root = std::sqrt(0.3);
  const LocatedEvent rising = locate(
      {{TriggerDirection::rising, [](double t) { return t * t - 0.3; },
        [](double t) { return 2.0 * t; }}},
      0.0, 1.0);
  ASSERT_TRUE(rising.found);
  EXPECT_EQ(rising.kind, CrossingKind::crossing);
  expect_near_ulps(rising.t, root, 4);
  // the negated witness falling: the same time to the bit (negation is exact)
  const LocatedEvent falling = locate(
      {{TriggerDirection::falling, [](double t) { return 0.3 - t * t; },
        [](double t) { return -2.0 * t; }}},
      0.0, 1.0);
  ASSERT_TRUE(falling.found);
  EXPECT_EQ(falling.t, rising.t);
}

TEST(EventLocation, MinimumWithinTheToleranceIsAGrazing) {
  const LocatedEvent touching = locate({parabola(0.47, 1e-13)}, 0.0, 1.0);
  ASSERT_TRUE(touching.found);
  EXPECT_EQ(touching.kind, CrossingKind::grazing);
  expect_near_ulps(touching.t, 0.47, 8);
  // the same minimum above the tolerance is no event
  EXPECT_FALSE(locate({parabola(0.47, 1e-9)}, 0.0, 1.0).found);
}

TEST(EventLocation, DipBetweenTwoSamplesIsACrossingBeforeItsMinimum) {
  // both samples around 0.47 are above zero; the minimum −1e-6 is below:
  // the crossing is at 0.47 − 1e-3
  const LocatedEvent event = locate({parabola(0.47, -1e-6)}, 0.0, 1.0);
  ASSERT_TRUE(event.found);
  EXPECT_EQ(event.kind, CrossingKind::crossing);
  expect_near_ulps(event.t, 0.47 - 1e-3, 8);
}

TEST(EventLocation, ViolationWithoutACrossingIsUnresolved) {
  // below zero by more than the tolerance from the step's start
  const LocatedEvent event = locate(
      {{TriggerDirection::falling, [](double) { return -1e-6; }, [](double) { return 0.0; }}},
      0.0, 1.0);
  ASSERT_TRUE(event.found);
  EXPECT_EQ(event.kind, CrossingKind::unresolved);
  EXPECT_EQ(event.t, 0.0);
}

TEST(EventLocation, EarliestOfSeveralWitnesses) {
  const auto line = [](double root) {
    return ClosedForm{TriggerDirection::falling, [=](double t) { return root - t; },
                      [](double) { return -1.0; }};
  };
  const LocatedEvent event = locate({line(0.7), line(0.3), line(0.5)}, 0.0, 1.0);
  ASSERT_TRUE(event.found);
  EXPECT_EQ(event.witness, 1u);
  expect_near_ulps(event.t, 0.3, 4);
}

TEST(EventLocation, CheapScanErrorNeverMovesOrHidesAnEvent) {
  // the interpolant is off by 1e-3 upwards: on it the dip below never shows
  // at its samples, and its crossing (where it has one) is 1e-3 out; the
  // accurate samples decide, and the root is the exact flow's
  const LocatedEvent crossing = locate(
      {{TriggerDirection::falling, [](double t) { return 1.0 - t * t; },
        [](double t) { return -2.0 * t; }}},
      0.0, 2.0, true, 1e-3);
  ASSERT_TRUE(crossing.found);
  expect_near_ulps(crossing.t, 1.0, 4);
  const LocatedEvent touching = locate({parabola(0.47, 1e-13)}, 0.0, 1.0, true, 1e-3);
  ASSERT_TRUE(touching.found);
  EXPECT_EQ(touching.kind, CrossingKind::grazing);
  expect_near_ulps(touching.t, 0.47, 8);
}

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
