// core/fast_trig.hpp against long double sinl and cosl (an independent
// implementation with 11 more bits): cos of a forcing phase of any size, sin
// of an angle, within a few ulps, and the library's functions where the fast
// paths do not apply. Fixed seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <numbers>
#include <random>

#include <impactlab/core/fast_trig.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

// |value − reference| in ulps of the reference rounded to double
double ulps(double value, long double reference) {
  const double rounded = static_cast<double>(reference);
  const double ulp = std::nextafter(std::fabs(rounded), INFINITY) - std::fabs(rounded);
  return static_cast<double>(std::fabs(static_cast<long double>(value) - reference)) / ulp;
}

TEST(FastTrig, CosOfAPhaseIsWithinThreeUlps) {
  std::mt19937_64 generator(20261121);
  std::uniform_real_distribution<double> phase(-2e4, 2e4);  // ωt over about 3000 periods
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double x = phase(generator);
    worst = std::max(worst, ulps(impactlab::cos_phase(x), cosl(static_cast<long double>(x))));
  }
  // near the quadrant boundaries and the zeros of cos, where the reduction matters
  for (long k = -20000; k <= 20000; k += 7) {
    for (double offset : {-1e-9, 0.0, 1e-9}) {
      const double x = static_cast<double>(k) * 0.5 * std::numbers::pi + offset;
      worst = std::max(worst, ulps(impactlab::cos_phase(x), cosl(static_cast<long double>(x))));
    }
  }
  RecordProperty("worst_ulps", std::to_string(worst));
  EXPECT_LE(worst, 3.0);
}

TEST(FastTrig, SinOfAnAngleIsWithinOneUlp) {
  std::mt19937_64 generator(7);
  std::uniform_real_distribution<double> angle(-0.25 * std::numbers::pi, 0.25 * std::numbers::pi);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double theta = angle(generator);
    worst = std::max(worst, ulps(impactlab::sin_angle(theta), sinl(static_cast<long double>(theta))));
  }
  EXPECT_LE(worst, 1.0);
  EXPECT_EQ(impactlab::sin_angle(0.0), 0.0);
  EXPECT_EQ(impactlab::cos_phase(0.0), 1.0);
}

// sin_cos_phase: both within a few ulps of sinl/cosl over phases and angles
// (the Taylor stepper's order-0 coefficients of sin θ and of cos ωt), its
// cosine cos_phase's and its sine sin_phase's bit for bit
TEST(FastTrig, SinAndCosTogetherAreWithinThreeUlps) {
  std::mt19937_64 generator(20261125);
  std::uniform_real_distribution<double> phase(-2e4, 2e4);
  double worst_sin = 0.0, worst_cos = 0.0;
  auto check = [&](double x) {
    double s = 0.0, c = 0.0;
    impactlab::sin_cos_phase(x, s, c);
    worst_sin = std::max(worst_sin, ulps(s, sinl(static_cast<long double>(x))));
    worst_cos = std::max(worst_cos, ulps(c, cosl(static_cast<long double>(x))));
    EXPECT_EQ(c, impactlab::cos_phase(x)) << x;
    EXPECT_EQ(s, impactlab::sin_phase(x)) << x;
  };
  for (int i = 0; i < 200000; ++i) check(phase(generator));
  for (long k = -20000; k <= 20000; k += 7)
    for (double offset : {-1e-9, 0.0, 1e-9}) check(static_cast<double>(k) * 0.5 * std::numbers::pi + offset);
  RecordProperty("worst_ulps_sin", std::to_string(worst_sin));
  RecordProperty("worst_ulps_cos", std::to_string(worst_cos));
  EXPECT_LE(worst_sin, 3.0);
  EXPECT_LE(worst_cos, 3.0);
  double s = 1.0, c = 0.0;
  impactlab::sin_cos_phase(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  for (double x : {2e6, -5e7, 1e15}) {
    impactlab::sin_cos_phase(x, s, c);
    EXPECT_EQ(s, std::sin(x));
    EXPECT_EQ(c, std::cos(x));
  }
}

TEST(FastTrig, OutsideTheFastRangesTheLibraryIsUsed) {
  for (double theta : {0.8, -1.2, 1.5, 3.0}) EXPECT_EQ(impactlab::sin_angle(theta), std::sin(theta));
  for (double x : {2e6, -5e7, 1e15}) EXPECT_EQ(impactlab::cos_phase(x), std::cos(x));
  for (double x : {2e6, -5e7, 1e15}) EXPECT_EQ(impactlab::sin_phase(x), std::sin(x));
}

}  // namespace
