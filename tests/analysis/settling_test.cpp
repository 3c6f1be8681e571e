// The settling test of a section run's transient (analysis/settling.hpp), on
// sequences whose fate is known in closed form: exact repeats, decays at a
// given multiplier, a chaotic map and a rotation by an irrational angle.
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/settling.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::SectionPoint;
using impactlab::settling_verdict;
using impactlab::SettlingVerdict;

constexpr int window = 64;       // the section run's default window (forcing periods)
constexpr int max_period = 16;
constexpr double tolerance = 1e-7;

// y_k = orbit[k mod p] + deviation(k)
template <class Deviation>
std::vector<SectionPoint> sequence(const std::vector<std::array<double, 2>>& orbit,
                                   Deviation deviation, int first = 0) {
  std::vector<SectionPoint> points;
  for (int k = first; k < first + window; ++k) {
    const auto& y = orbit[static_cast<std::size_t>(k) % orbit.size()];
    const std::array<double, 2> d = deviation(k);
    points.push_back({static_cast<double>(k), y[0] + d[0], y[1] + d[1], 0});
  }
  return points;
}

const std::vector<std::array<double, 2>> period_three = {{0.04, -0.3}, {-0.02, 0.5}, {0.01, 0.1}};
const std::vector<std::array<double, 2>> period_two = {{0.0421, -0.0132}, {-0.0368, 0.0265}};

TEST(Settling, PointsThatRepeatToTheToleranceHaveSettled) {
  const auto exact = sequence(period_three, [](int) { return std::array<double, 2>{}; });
  EXPECT_EQ(settling_verdict(exact, max_period, tolerance), SettlingVerdict::settled);
  // a residue a little under the tolerance (relative to 1 + |y|) still counts
  const auto close = sequence(period_three, [](int k) {
    return std::array<double, 2>{0.4 * tolerance * std::sin(k), 0.0};
  });
  EXPECT_EQ(settling_verdict(close, max_period, tolerance), SettlingVerdict::settled);
  // the rest itself: every point the same
  const auto rest = sequence({{0.0, 0.0}}, [](int) { return std::array<double, 2>{}; });
  EXPECT_EQ(settling_verdict(rest, max_period, tolerance), SettlingVerdict::settled);
}

// The friction sweep's unsettled label: a period-2 orbit whose multiplier
// −0.9967 leaves 0.81 of a deviation after 64 periods, each of the two
// points approached at its own distance. Its points almost repeat every 4
// periods, which a fixed transient labelled period 4.
TEST(Settling, ASlowDecayAtARealMultiplierIsStillConverging) {
  const double multiplier = -0.9967;
  for (int first : {0, 100, 1000}) {
    SCOPED_TRACE(first);
    const auto slow = sequence(
        period_two,
        [&](int k) {
          const double size = (k % 2 == 0 ? 1e-3 : 4e-3) * std::pow(multiplier, k / 2);
          return std::array<double, 2>{size, -0.3 * size};
        },
        first);
    EXPECT_EQ(settling_verdict(slow, max_period, tolerance), SettlingVerdict::converging);
  }
  // the same decay once it is small: after 4 periods the points repeat to
  // 1.3e-8, under the tolerance, but after 2 they are 4e-6 apart and that
  // distance still shrinks. A fixed transient labelled this period 4.
  const auto small = sequence(period_two, [&](int k) {
    const double size = 2e-6 * std::pow(multiplier, k / 2);
    return std::array<double, 2>{size, size};
  });
  EXPECT_EQ(settling_verdict(small, max_period, tolerance), SettlingVerdict::converging);
  // the decaying hanging rest: one point, approached at 0.975 per period
  const auto rest = sequence({{0.0, 0.0}}, [](int k) {
    const double size = 1e-2 * std::pow(0.975, k);
    return std::array<double, 2>{size, 0.5 * size};
  });
  EXPECT_EQ(settling_verdict(rest, max_period, tolerance), SettlingVerdict::converging);
}

// A focus: complex multipliers 0.97 e^{±1.1 i} seen through an elliptic
// change of coordinates, so the distances between points oscillate while
// their envelope shrinks.
TEST(Settling, ASpiralWhoseEnvelopeShrinksIsStillConverging) {
  const auto spiral = sequence(period_three, [](int k) {
    const double size = 1e-2 * std::pow(0.97, k);
    return std::array<double, 2>{5.0 * size * std::cos(1.1 * k), size * std::sin(1.1 * k)};
  });
  EXPECT_EQ(settling_verdict(spiral, max_period, tolerance), SettlingVerdict::converging);
}

TEST(Settling, AChaoticMotionIsNotPeriodic) {
  // the logistic map at r = 4, (x_k, x_{k+1}): chaotic, never repeating
  std::vector<SectionPoint> chaotic;
  double x = 0.1234567;
  for (int warm = 0; warm < 100; ++warm) x = 4.0 * x * (1.0 - x);
  for (int k = 0; k < window; ++k) {
    const double next = 4.0 * x * (1.0 - x);
    chaotic.push_back({static_cast<double>(k), x, next, 0});
    x = next;
  }
  EXPECT_EQ(settling_verdict(chaotic, max_period, tolerance), SettlingVerdict::not_periodic);
}

TEST(Settling, AQuasiPeriodicMotionIsNotPeriodic) {
  // a rotation by the golden angle on a circle: a torus, neither repeating
  // nor converging
  const double angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const auto torus = sequence({{0.0, 0.0}}, [&](int k) {
    return std::array<double, 2>{0.1 * std::cos(angle * k), 0.1 * std::sin(angle * k)};
  });
  EXPECT_EQ(settling_verdict(torus, max_period, tolerance), SettlingVerdict::not_periodic);
}

// A period longer than the longest looked for is not a repeat: the
// transient ends as not_periodic, as a period the sweep cannot label.
TEST(Settling, APeriodLongerThanTheLongestLookedForIsNotPeriodic) {
  std::vector<std::array<double, 2>> long_orbit;
  for (int k = 0; k < 20; ++k) long_orbit.push_back({0.01 * std::sin(2.7 * k), 0.02 * k});
  const auto points = sequence(long_orbit, [](int) { return std::array<double, 2>{}; });
  EXPECT_EQ(settling_verdict(points, 16, tolerance), SettlingVerdict::not_periodic);
  EXPECT_EQ(settling_verdict(points, 20, tolerance), SettlingVerdict::settled);
}

}  // namespace
