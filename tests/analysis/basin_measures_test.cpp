// Basin measures (analysis/basin_measures.hpp) on label grids whose answers
// are known in closed form, written here:
// * a straight boundary between columns: a box cut a : (ε − a) has entropy
//   h(a/ε) = −(a/ε) ln(a/ε) − (1 − a/ε) ln(1 − a/ε), one column of boxes is
//   cut, and f(k) = 2k / nx exactly, so α = 1 and d = 1;
// * a checkerboard in boxes of even side: every box half and half, S_b = S_bb
//   = ln 2 exactly;
// * independent fair labels: f(k) is nearly constant (1 − 2⁻⁴ inside), α ≈ 0,
//   and a box's mean entropy is the binomial expectation Σ_m C(n, m) 2⁻ⁿ h(m/n);
// * the Weierstrass-type boundary y < Σ_k b^{−kH} cos(b^k x): a graph of box
//   dimension 2 − H, so α = H.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/basin_measures.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::basin_measures;
using impactlab::BasinMeasures;

// the two-label Gibbs entropy of shares p and 1 − p (nats)
double binary_entropy(double p) {
  if (p <= 0.0 || p >= 1.0) return 0.0;
  return -p * std::log(p) - (1.0 - p) * std::log(1.0 - p);
}

// labels 1 left of column `boundary`, 2 from it on
std::vector<int> straight_boundary(int nx, int ny, int boundary) {
  std::vector<int> labels(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) labels[static_cast<std::size_t>(j) * nx + i] = i < boundary ? 1 : 2;
  return labels;
}

TEST(BasinMeasures, StraightBoundaryHasExponentOneAndSmallBoundaryEntropy) {
  const int n = 1000, box = 5, boundary = 502;  // boxes cut 2 : 3
  const BasinMeasures m = basin_measures(straight_boundary(n, n, boundary), n, n, box);
  const double cut_entropy = binary_entropy(2.0 / 5.0);
  EXPECT_EQ(m.labels, 2);
  EXPECT_EQ(m.boxes, (n / box) * (n / box));
  EXPECT_EQ(m.boundary_boxes, n / box);
  EXPECT_NEAR(m.boundary_basin_entropy, cut_entropy, 1e-12);
  EXPECT_NEAR(m.basin_entropy, cut_entropy / (n / box), 1e-12);
  EXPECT_LT(m.boundary_basin_entropy, std::log(2.0));
  EXPECT_FALSE(m.fractal_by_log2);
  // k = 1, 2, ..., 128 (4k ≤ 1000), each f(k) = 2k/n
  ASSERT_EQ(m.scales.size(), 8u);
  for (std::size_t s = 0; s < m.scales.size(); ++s) {
    EXPECT_EQ(m.scales[s], 1 << s);
    EXPECT_NEAR(m.uncertain_fraction[s], 2.0 * m.scales[s] / n, 1e-12);
  }
  EXPECT_NEAR(m.uncertainty_exponent, 1.0, 1e-9);
  EXPECT_NEAR(m.uncertainty_exponent_error, 0.0, 1e-9);
  EXPECT_NEAR(m.boundary_dimension, 1.0, 1e-9);
}

TEST(BasinMeasures, CheckerboardInEvenBoxesHasEntropyLogTwo) {
  const int n = 40, box = 4;
  std::vector<int> labels(n * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) labels[j * n + i] = (i + j) % 2 == 0 ? 1 : 2;
  const BasinMeasures m = basin_measures(labels, n, n, box);
  EXPECT_NEAR(m.basin_entropy, std::log(2.0), 1e-12);
  EXPECT_NEAR(m.boundary_basin_entropy, std::log(2.0), 1e-12);
  EXPECT_EQ(m.boundary_boxes, m.boxes);
  EXPECT_FALSE(m.fractal_by_log2);  // ln 2 itself is not above ln 2
}

// independent fair labels 1 and 2 (a fixed seed; the bits of mt19937, the
// same on every standard library)
std::vector<int> random_labels(int nx, int ny) {
  std::mt19937 bits(20160809);
  std::vector<int> labels(static_cast<std::size_t>(nx) * ny);
  for (int& label : labels) label = 1 + static_cast<int>(bits() & 1u);
  return labels;
}

TEST(BasinMeasures, RandomLabelsHaveMaximalEntropyAndExponentNearZero) {
  const int n = 400, box = 5, box_points = box * box;
  const BasinMeasures m = basin_measures(random_labels(n, n), n, n, box);
  // the binomial expectation of a box's entropy
  double expected = 0.0;
  for (int count = 0; count <= box_points; ++count) {
    const double ways = std::exp(std::lgamma(box_points + 1.0) - std::lgamma(count + 1.0) -
                                 std::lgamma(box_points - count + 1.0));
    expected += ways * std::pow(0.5, box_points) * binary_entropy(double(count) / box_points);
  }
  // 6400 boxes: the mean is within a few 0.001 of the expectation
  EXPECT_NEAR(m.basin_entropy, expected, 0.005);
  EXPECT_NEAR(m.boundary_basin_entropy, expected, 0.005);
  EXPECT_GT(expected, std::log(2.0) - 0.03);  // near the two-label maximum
  // an inside point is certain only when its four neighbours agree with it
  EXPECT_NEAR(m.uncertain_fraction.front(), 1.0 - 1.0 / 16.0, 0.01);
  EXPECT_NEAR(m.uncertainty_exponent, 0.0, 0.03);
  EXPECT_NEAR(m.boundary_dimension, 2.0, 0.03);
}

// y < W(x) = Σ_k b^{−kH} cos(b^k x), x over one period [0, 2π) on nx
// columns, y over [−W_max, W_max] on ny rows; the terms go down to the grid's
// spacing
std::vector<int> weierstrass_boundary(int n, double H, double b) {
  const int terms = static_cast<int>(std::ceil(std::log(n) / std::log(b))) + 2;
  double amplitude = 0.0;
  for (int k = 0; k < terms; ++k) amplitude += std::pow(b, -k * H);
  std::vector<int> labels(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i) {
    const double x = 2.0 * std::numbers::pi * i / n;
    double w = 0.0;
    for (int k = 0; k < terms; ++k) w += std::pow(b, -k * H) * std::cos(std::pow(b, k) * x);
    for (int j = 0; j < n; ++j) {
      const double y = ((j + 0.5) / n * 2.0 - 1.0) * amplitude;
      labels[static_cast<std::size_t>(j) * n + i] = y < w ? 1 : 2;
    }
  }
  return labels;
}

TEST(BasinMeasures, WeierstrassBoundaryHasExponentH) {
  const int n = 1024;
  const double H = 0.7;
  const BasinMeasures m = basin_measures(weierstrass_boundary(n, H, 3.0), n, n, 5);
  EXPECT_EQ(m.scales.back(), 256);
  // the fit's error, and finite-grid bias well under the box dimension's span
  EXPECT_LT(std::abs(m.uncertainty_exponent - H), 3.0 * m.uncertainty_exponent_error);
  EXPECT_NEAR(m.uncertainty_exponent, H, 0.03);
  EXPECT_NEAR(m.boundary_dimension, 2.0 - H, 0.03);
}

TEST(BasinMeasures, EntropiesOrderSmoothBelowFractalBelowRandom) {
  const int n = 1000, box = 5;
  const BasinMeasures smooth = basin_measures(straight_boundary(n, n, 502), n, n, box);
  const BasinMeasures fractal = basin_measures(weierstrass_boundary(n, 0.5, 3.0), n, n, box);
  const BasinMeasures random = basin_measures(random_labels(n, n), n, n, box);
  EXPECT_LT(smooth.basin_entropy, fractal.basin_entropy);
  EXPECT_LT(fractal.basin_entropy, random.basin_entropy);
  EXPECT_LT(fractal.boundary_basin_entropy, random.boundary_basin_entropy);
  EXPECT_GT(fractal.boundary_boxes, smooth.boundary_boxes);
  EXPECT_LT(smooth.uncertainty_exponent, 1.0 + 1e-9);
  EXPECT_GT(smooth.uncertainty_exponent, fractal.uncertainty_exponent);
  EXPECT_GT(fractal.uncertainty_exponent, random.uncertainty_exponent);
}

TEST(BasinMeasures, NoneFoundIsALabelOfItsOwn) {
  // a 10 × 10 grid, label 0 left of column 5, 1 from it: one boundary
  std::vector<int> labels = straight_boundary(10, 10, 5);
  for (int& label : labels) label -= 1;
  const BasinMeasures m = basin_measures(labels, 10, 10, 5);
  EXPECT_EQ(m.labels, 2);
  EXPECT_EQ(m.boundary_boxes, 0);  // the boundary runs along box edges
  EXPECT_EQ(m.basin_entropy, 0.0);
  EXPECT_TRUE(std::isnan(m.boundary_basin_entropy));
  EXPECT_NEAR(m.uncertain_fraction.front(), 0.2, 1e-12);  // columns 4 and 5
}

TEST(BasinMeasures, OneLabelHasNoBoundary) {
  const BasinMeasures m = basin_measures(std::vector<int>(64, 3), 8, 8, 4);
  EXPECT_EQ(m.basin_entropy, 0.0);
  EXPECT_EQ(m.boundary_boxes, 0);
  EXPECT_TRUE(std::isnan(m.uncertainty_exponent));
}

TEST(BasinMeasures, BoxLargerThanTheGridIsRefused) {
  EXPECT_THROW(basin_measures(std::vector<int>(30 * 4, 1), 30, 4, 5), std::invalid_argument);
  EXPECT_THROW(basin_measures(std::vector<int>(10, 1), 3, 4, 2), std::invalid_argument);
  EXPECT_THROW(basin_measures(std::vector<int>(16, 1), 4, 4, 0), std::invalid_argument);
}

}  // namespace
