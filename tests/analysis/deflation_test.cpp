// Deflation (analysis/deflation.hpp) against its definition: M(x) =
// Π_i ((ρ/|x − r_i|)^p + σ) evaluated by hand, ∇ log M against central
// differences of log M, and the deflated step (Sherman–Morrison) against
// Newton's step on G = M F itself, its Jacobian by central differences, for
// an affine F whose Newton step is known exactly; no step on a known root.
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/deflation.hpp>

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

using Vector = std::array<double, 2>;

Deflation two_roots() {
  Deflation deflation;
  deflation.roots = {{0.3, -0.2}, {-0.5, 0.4}};
  return deflation;
}

TEST(Deflation, NoRootsLeavesNewtonAlone) {
  const Deflation none;
  const Vector x = {0.7, -1.1};
  EXPECT_EQ(deflation_factor(none, x), 1.0);
  Vector step = {0.25, -0.5};
  EXPECT_TRUE(deflate_step(none, x, step));
  EXPECT_EQ(step[0], 0.25);
  EXPECT_EQ(step[1], -0.5);
}

TEST(Deflation, FactorIsTheProductOverTheKnownRoots) {
  const Deflation deflation = two_roots();
  const Vector x = {0.1, 0.05};
  double expected = 1.0;
  for (const auto& r : deflation.roots) {
    const double d = std::hypot(x[0] - r[0], x[1] - r[1]);
    expected *= std::pow(deflation.radius / d, deflation.power) + deflation.shift;
  }
  EXPECT_NEAR(deflation_factor(deflation, x), expected, 1e-14 * expected);
  // far from both roots M tends to σ² = 1
  const Vector far = {1e6, -1e6};
  EXPECT_NEAR(deflation_factor(deflation, far), 1.0, 1e-12);
}

TEST(Deflation, LogGradientMatchesCentralDifferences) {
  const Deflation deflation = two_roots();
  const Vector x = {0.12, 0.07};
  Vector gradient{};
  deflation_log_gradient(deflation, x, gradient);
  const double h = 1e-6;
  for (std::size_t i = 0; i < 2; ++i) {
    Vector up = x, down = x;
    up[i] += h;
    down[i] -= h;
    const double difference = (std::log(deflation_factor(deflation, up)) -
                               std::log(deflation_factor(deflation, down))) / (2.0 * h);
    EXPECT_NEAR(gradient[i], difference, 1e-6 * (1.0 + std::abs(difference))) << i;
  }
}

TEST(Deflation, StepIsNewtonsStepOnTheDeflatedFunction) {
  // F(x) = A (x − x*): Newton's step δ_F = x* − x
  const double a[2][2] = {{2.0, 0.5}, {-0.3, 1.5}};
  const Vector root = {0.9, -0.6};
  const Deflation deflation = two_roots();
  const auto F = [&](const Vector& x) {
    return Vector{a[0][0] * (x[0] - root[0]) + a[0][1] * (x[1] - root[1]),
                  a[1][0] * (x[0] - root[0]) + a[1][1] * (x[1] - root[1])};
  };
  const auto G = [&](const Vector& x) {
    const double m = deflation_factor(deflation, x);
    const Vector f = F(x);
    return Vector{m * f[0], m * f[1]};
  };
  const Vector x = {0.2, 0.15};
  Vector step = {root[0] - x[0], root[1] - x[1]};
  ASSERT_TRUE(deflate_step(deflation, x, step));
  // Newton on G: J_G by central differences, δ = −J_G⁻¹ G(x) (Cramer)
  const double h = 1e-7;
  double j[2][2];
  for (std::size_t c = 0; c < 2; ++c) {
    Vector up = x, down = x;
    up[c] += h;
    down[c] -= h;
    const Vector gu = G(up), gd = G(down);
    for (std::size_t r = 0; r < 2; ++r) j[r][c] = (gu[r] - gd[r]) / (2.0 * h);
  }
  const Vector g = G(x);
  const double det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
  const Vector newton = {(-g[0] * j[1][1] + g[1] * j[0][1]) / det,
                         (-j[0][0] * g[1] + j[1][0] * g[0]) / det};
  for (std::size_t i = 0; i < 2; ++i)
    EXPECT_NEAR(step[i], newton[i], 1e-6 * (1.0 + std::abs(newton[i]))) << i;
  // and it is not the undeflated step: the known roots push it
  EXPECT_GT(std::hypot(step[0] - (root[0] - x[0]), step[1] - (root[1] - x[1])), 1e-3);
}

TEST(Deflation, NoStepOnAKnownRoot) {
  const Deflation deflation = two_roots();
  const Vector on_root = {0.3, -0.2};
  Vector step = {0.1, 0.1};
  EXPECT_FALSE(deflate_step(deflation, on_root, step));
}

}  // namespace
}  // namespace impactlab
