// The series of several trajectories in one pass over lanes
// (integrate/series_tape.hpp) against the series of double of each alone
// (integrate/taylor_series.hpp), coefficient by coefficient, to the last bit:
// every kind of operation a tape holds, lanes of different constants and
// states, and what makes two tapes different.
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include <impactlab/integrate/series_tape.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

constexpr std::size_t dimension = 3;
constexpr int order = 20;

// A right-hand side that runs every operation of a tape: sums, differences
// and negation, constants that scale and shift, products with the time's
// polynomial and of two series, quotients (a series by a series, a constant
// by a series, a series by one constant over the step), sin and cos of a
// state component, of ωt, of a product and of a sign, fabs, exp (of a
// series, of a sign and of ωt), log, √, a power whose exponent is the
// lane's own, and outputs that are a constant, the time and an operation.
// `p` is a lane's parameter: the constants differ from lane to lane.
struct EveryOperation {
  double p = 1.0;
  bool branch = false;  // a value-independent switch of the operations
  template <class X, class T, class Outputs>
  int operator()(const X& x, const T& t, X& dxdt, Outputs& outputs) const {
    using std::cos;
    using std::exp;
    using std::log;
    using std::pow;
    using std::sin;
    using std::sqrt;
    const auto wt = (2.0 * p) * t + 0.3;
    const auto s = sign(x[1] - 0.05);
    dxdt[0] = -(-x[1]);
    dxdt[1] = -p * sin(x[0]) + 0.5 * cos(wt) * x[2] - fabs(x[1]) * x[1] +
              (1.0 + p) / (2.0 + x[0] * x[0]) + sin(s * x[0]) * 0.01 + sin(s) * 0.02 +
              x[2] / (s + 3.0) * 0.1;
    dxdt[2] = branch ? -x[2] : (x[0] - x[2]) / (1.5 + cos(x[0] * x[1])) - t * t * p;
    outputs[0] = p - x[0];
    outputs[1] = 0.25 * p;
    outputs[2] = t;
    outputs[3] = 1.0 - x[1] * (3.0 - x[0]);
    outputs[4] = exp(0.3 * x[0]) * sqrt(2.0 + x[1] * x[1]) + exp(0.1 * s);
    outputs[5] = log(3.0 + x[2]) + pow(1.5 + x[0] * x[0], 0.5 * p + 0.25) + exp(wt * 0.1);
    return 6;
  }
};

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

struct Lane {
  std::array<double, dimension> x0;
  double t0;
  EveryOperation rhs;
};

// each lane alone in double
std::unique_ptr<TaylorSeries<double, dimension>> alone(const Lane& lane) {
  auto series = std::make_unique<TaylorSeries<double, dimension>>();
  series->evaluate(lane.x0.data(), lane.t0, order, lane.rhs);
  return series;
}

void expect_lanes_equal_alone(const std::array<Lane, tape_lane_width>& lanes, int count) {
  std::array<std::unique_ptr<SeriesTape>, tape_lane_width> tapes;
  std::array<const SeriesTape*, tape_lane_width> views{};
  for (int i = 0; i < count; ++i) {
    tapes[i] = std::make_unique<SeriesTape>();
    record_series_tape<dimension>(*tapes[i], lanes[i].x0.data(), lanes[i].t0, lanes[i].rhs);
    views[i] = tapes[i].get();
    ASSERT_TRUE(tapes[i]->same_operations(*tapes[0])) << "lane " << i;
  }
  auto rows = std::make_unique<SeriesLaneRows>();
  replay_series_tapes(views, count, order, *rows);
  for (int i = 0; i < count; ++i) {
    SCOPED_TRACE("lane " + std::to_string(i));
    const auto expected = alone(lanes[i]);
    auto taken = std::make_unique<TaylorSeries<double, dimension>>();
    taken->take_lane(*rows, *tapes[i], i, order);
    EXPECT_EQ(taken->needs_slope(), expected->needs_slope());
    ASSERT_EQ(taken->output_count(), expected->output_count());
    for (int k = 0; k <= order; ++k) {
      for (std::size_t c = 0; c < dimension; ++c)
        EXPECT_EQ(bits(taken->state(c)[k]), bits(expected->state(c)[k]))
            << "state " << c << " order " << k << ": " << taken->state(c)[k] << " vs "
            << expected->state(c)[k];
      for (int j = 0; j < expected->output_count(); ++j)
        EXPECT_EQ(bits(taken->output(j)[k]), bits(expected->output(j)[k]))
            << "output " << j << " order " << k;
    }
    // the same coefficients read in place, as a stepper in a batch reads them
    const int stride = rows->lane_stride();
    for (int k = 0; k <= order; ++k) {
      for (std::size_t c = 0; c < dimension; ++c)
        EXPECT_EQ(bits(rows->lane_coefficients(static_cast<int>(c), i)[k * stride]),
                  bits(expected->state(c)[k]))
            << "state " << c << " order " << k << " in place";
      for (int j = 0; j < expected->output_count(); ++j)
        EXPECT_EQ(bits(rows->lane_coefficients(tapes[i]->output_row(j), i)[k * stride]),
                  bits(expected->output(j)[k]))
            << "output " << j << " order " << k << " in place";
    }
  }
}

TEST(SeriesTape, AFullPassOfDifferentConstantsEqualsTheSeriesOfDoubleBitForBit) {
  static_assert(tape_lane_width == 8);
  const std::array<Lane, tape_lane_width> lanes = {
      Lane{{0.3, 0.2, -0.1}, 0.0, {1.0}},     Lane{{-0.7, 1.1, 0.4}, 2.5, {0.35}},
      Lane{{1.2, -0.4, 0.0}, 10.0, {2.75}},   Lane{{0.01, 0.06, 3.0}, 0.125, {-1.5}},
      Lane{{-0.2, 0.9, 1.3}, 7.0, {0.8}},     Lane{{0.45, -1.6, -0.3}, 1.75, {1.25}},
      Lane{{2.1, 0.33, 0.05}, 4.5, {-0.6}},   Lane{{-1.05, -0.02, 2.2}, 0.5, {3.1}}};
  expect_lanes_equal_alone(lanes, tape_lane_width);
  // the coefficients are not trivial: the series of x1 reaches order 20
  const auto series = alone(lanes[1]);
  EXPECT_NE(series->state(1)[order], 0.0);
}

TEST(SeriesTape, APassOfFewerLanesThanItsWidthEqualsTheSeriesOfDouble) {
  const std::array<Lane, tape_lane_width> lanes = {
      Lane{{0.3, 0.2, -0.1}, 1.0, {1.5}},   Lane{{0.5, -0.9, 0.7}, 3.0, {0.5}},
      Lane{{-0.6, 0.4, 0.9}, 2.0, {1.1}},   Lane{{0.15, 1.3, -0.4}, 6.0, {2.2}},
      Lane{{1.4, -0.25, 0.35}, 0.75, {0.9}}};
  expect_lanes_equal_alone(lanes, 2);
  // lanes in the second quad, the spare ones repeating the first lane
  expect_lanes_equal_alone(lanes, 5);
}

// A sign whose argument starts at a zero it is leaving: the lane says so, as
// the series of double does, so that the stepper evaluates it again alone.
TEST(SeriesTape, ASignAtItsZeroAsksForItsSlopeLikeTheSeriesOfDouble) {
  const std::array<Lane, tape_lane_width> lanes = {Lane{{0.3, 0.05, -0.1}, 0.0, {1.0}},
                                                   Lane{{0.3, 0.2, -0.1}, 0.0, {1.0}}};
  expect_lanes_equal_alone(lanes, 2);
  EXPECT_TRUE(alone(lanes[0])->needs_slope());
  EXPECT_FALSE(alone(lanes[1])->needs_slope());
}

TEST(SeriesTape, TapesDifferWhereTheOperationsDoNotWhereOnlyTheirValuesDo) {
  const double x0[dimension] = {0.3, 0.2, -0.1};
  const double x1[dimension] = {-2.0, 7.0, 1.0};
  SeriesTape a, b, c;
  record_series_tape<dimension>(a, x0, 0.0, EveryOperation{1.0, false});
  record_series_tape<dimension>(b, x1, 4.0, EveryOperation{-3.0, false});
  record_series_tape<dimension>(c, x0, 0.0, EveryOperation{1.0, true});
  EXPECT_TRUE(a.same_operations(b));
  EXPECT_FALSE(a.same_operations(c));
  EXPECT_FALSE(c.same_operations(a));
}

// Each pass of a round takes rows of its own, which stay until the round
// ends; past its capacity the pool refuses.
TEST(SeriesTape, EachPassOfARoundHasRowsOfItsOwnUntilTheNextRound) {
  SeriesLaneRowsPool pool;
  std::array<const SeriesLaneRows*, SeriesLaneRowsPool::capacity> taken{};
  for (int i = 0; i < SeriesLaneRowsPool::capacity; ++i) {
    taken[i] = &pool.take();
    for (int j = 0; j < i; ++j) EXPECT_NE(taken[i], taken[j]) << "passes " << i << " and " << j;
  }
  EXPECT_THROW(pool.take(), std::logic_error);
  pool.start_round();
  EXPECT_EQ(&pool.take(), taken[0]);
}

}  // namespace
