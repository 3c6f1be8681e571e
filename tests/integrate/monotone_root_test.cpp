// The root of a monotone polynomial piece (integrate/monotone_root.hpp):
// against a root found by bisection in 50 significant digits on the same
// coefficients; the end it returns on the far side of the crossing; and
// the roots refined together in lanes equal to the last bit those refined
// alone.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <gtest/gtest.h>

#include <impactlab/integrate/monotone_root.hpp>
#include <impactlab/integrate/polynomial_roots.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;
using Precise = boost::multiprecision::cpp_bin_float_50;

// A problem with its coefficients held.
struct HeldProblem {
  std::array<double, taylor_max_order + 1> p{};
  std::array<double, taylor_max_order + 1> dp{};
  std::array<double, taylor_max_order + 1> ddp{};
  MonotoneRootProblem<double> problem;

  void point_into_self() {
    problem.p = p.data();
    problem.dp = dp.data();
    problem.ddp = ddp.data();
  }
};

// A problem held in `held`: P(h) = c0 + s h + Σ_{j≥2} c_j h^j on
// [lo, hi] ⊂ [0, 1], with |c_j| ≤ 1/(2 j³), so that Σ_{j≥2} j |c_j| < 1/3
// and |P′| > 2/3 there: monotone, falling (s = −1) or rising; c0 puts its
// root at a random point inside. The degree is 1..22, the size of the time
// 0, 1 or 1000 s.
void fill_random_problem(std::mt19937_64& random, HeldProblem& held) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  held = HeldProblem{};
  const int degree = 1 + static_cast<int>(random() % 22);
  const double slope = random() % 2 == 0 ? -1.0 : 1.0;
  held.p[1] = slope;
  for (int j = 2; j <= degree; ++j)
    held.p[j] = (unit(random) - 0.5) / (static_cast<double>(j) * j * j);
  const double lo = 0.3 * unit(random), hi = 0.7 + 0.3 * unit(random);
  const double root = lo + (hi - lo) * (0.02 + 0.96 * unit(random));
  held.p[0] = -polynomial_at(held.p, degree, root);
  for (int j = 0; j < degree; ++j) held.dp[j] = held.p[j + 1] * (j + 1);
  for (int j = 0; j + 1 < degree; ++j) held.ddp[j] = held.dp[j + 1] * (j + 1);
  const std::array<double, 3> scales = {0.0, 1.0, 1000.0};
  held.problem.degree = degree;
  held.problem.lo = lo;
  held.problem.hi = hi;
  held.problem.f_lo = polynomial_at(held.p, degree, lo);
  held.problem.f_hi = polynomial_at(held.p, degree, hi);
  held.problem.t_scale = scales[random() % 3];
  held.problem.towards_hi = random() % 2 == 0;
  held.point_into_self();
}

// the root of the same coefficients, by bisection in 50 digits
Precise precise_root(const HeldProblem& held) {
  auto value = [&](const Precise& h) {
    Precise sum = 0;
    for (int j = held.problem.degree; j >= 0; --j) sum = sum * h + Precise(held.p[j]);
    return sum;
  };
  Precise a = held.problem.lo, b = held.problem.hi;
  const bool rising_from_a = value(a) < 0;
  for (int i = 0; i < 200; ++i) {
    const Precise m = (a + b) / 2;
    if ((value(m) < 0) == rising_from_a)
      a = m;
    else
      b = m;
  }
  return (a + b) / 2;
}

// Within the tolerance of the true root of its coefficients, 4 ε (s + |h|)
// wide, plus the double polynomial's own round-off near the root (its
// value's error, about 1e-16 · Σ|c_j|, over its slope, at least 2/3); and
// the end past the crossing has P on f_hi's side (or zero) in double.
TEST(MonotoneRoot, WithinTheToleranceOfA50DigitRoot) {
  std::mt19937_64 random(20261202);
  const double epsilon = std::numeric_limits<double>::epsilon();
  for (int trial = 0; trial < 3000; ++trial) {
    HeldProblem held;
    fill_random_problem(random, held);
    const MonotoneRootProblem<double>& problem = held.problem;
    ASSERT_LT(problem.f_lo * problem.f_hi, 0.0) << trial;
    const double root = refine_monotone_root(problem);
    const double reference = static_cast<double>(precise_root(held));
    const double allowed = 4 * epsilon * (problem.t_scale + std::fabs(root)) + 8 * epsilon;
    EXPECT_LE(std::fabs(root - reference), allowed)
        << "trial " << trial << ", degree " << problem.degree << ", scale " << problem.t_scale;
    EXPECT_GE(root, problem.lo) << trial;
    EXPECT_LE(root, problem.hi) << trial;
    if (problem.towards_hi) {
      const double at_root = polynomial_at(held.p, problem.degree, root);
      EXPECT_TRUE(at_root == 0 || (at_root > 0) == (problem.f_hi > 0)) << trial;
    }
  }
}

// A chatter's crossing: the bracket starts at the witness's apex, where its
// slope is zero, and the root lies a small way past it (the
// witness after a slow rebound, g(h) = δ − c (h − u)² + small higher terms
// on [u, 1/4]): within the tolerance of the 50-digit root, for apexes and
// rebounds over six decades.
TEST(MonotoneRoot, AChattersCrossingJustPastTheApex) {
  const double epsilon = std::numeric_limits<double>::epsilon();
  for (const double apex : {1e-6, 1e-4, 1e-2}) {
    for (const double rebound : {1e-12, 1e-9, 1e-6}) {
      HeldProblem held;
      const int degree = 12;
      // δ − 0.2 (h − u)² + 0.01 h³ …: expanded in h
      held.p[0] = rebound - 0.2 * apex * apex;
      held.p[1] = 0.4 * apex;
      held.p[2] = -0.2;
      for (int j = 3; j <= degree; ++j) held.p[j] = 0.01 / (j * j);
      for (int j = 0; j < degree; ++j) held.dp[j] = held.p[j + 1] * (j + 1);
      for (int j = 0; j + 1 < degree; ++j) held.ddp[j] = held.dp[j + 1] * (j + 1);
      held.problem.degree = degree;
      held.problem.lo = apex;
      held.problem.hi = 0.25;
      held.problem.f_lo = polynomial_at(held.p, degree, apex);
      held.problem.f_hi = polynomial_at(held.p, degree, 0.25);
      held.problem.t_scale = 2.0;
      held.problem.towards_hi = true;
      held.point_into_self();
      ASSERT_GT(held.problem.f_lo, 0.0);
      ASSERT_LT(held.problem.f_hi, 0.0);
      const double root = refine_monotone_root(held.problem);
      const double reference = static_cast<double>(precise_root(held));
      EXPECT_LE(std::fabs(root - reference), 4 * epsilon * (2.0 + root) + 8 * epsilon)
          << "apex " << apex << ", rebound " << rebound;
      EXPECT_LE(polynomial_at(held.p, degree, root), 0.0) << apex << " " << rebound;
    }
  }
}

// A root that an iterate hits exactly is returned exactly: P(h) = h − 1/2,
// whose chord through the ends of [0, 1] crosses zero at 1/2.
TEST(MonotoneRoot, AnExactZeroIsTheRoot) {
  const std::array<double, 2> p = {-0.5, 1.0};
  const std::array<double, 1> dp = {1.0};
  for (const bool towards_hi : {false, true}) {
    const MonotoneRootProblem<double> problem{p.data(), dp.data(), nullptr, 1, 0.0, 1.0, -0.5, 0.5,
                                              1.0, towards_hi};
    EXPECT_EQ(refine_monotone_root(problem), 0.5);
  }
}

// Problems of different degrees, intervals, scales and sides, refined 1 to
// 16 at a time in lanes: each root is, to the last bit, the one refined
// alone.
TEST(MonotoneRoot, LanesEqualTheRootsRefinedAlone) {
  std::mt19937_64 random(7);
  for (int count = 1; count <= max_series_lanes; ++count) {
    for (int round = 0; round < 40; ++round) {
      std::vector<HeldProblem> held(static_cast<std::size_t>(count));
      for (auto& one : held) fill_random_problem(random, one);
      std::vector<const MonotoneRootProblem<double>*> problems;
      for (const auto& one : held) problems.push_back(&one.problem);
      std::vector<double> roots(static_cast<std::size_t>(count));
      refine_monotone_roots(problems.data(), count, roots.data());
      for (int i = 0; i < count; ++i) {
        const double alone = refine_monotone_root(held[static_cast<std::size_t>(i)].problem);
        const double in_lanes = roots[static_cast<std::size_t>(i)];
        EXPECT_EQ(std::memcmp(&alone, &in_lanes, sizeof alone), 0)
            << "lane " << i << " of " << count << ": " << in_lanes << " against " << alone;
      }
    }
  }
}

// PolynomialRoots' roots are the refinement's: the crossing of a witness
// that falls through zero, as the Taylor stepper's event location asks for
// it (the end past the crossing).
TEST(MonotoneRoot, PolynomialRootsAsksForTheEndPastTheCrossing) {
  // 0.3 − h − 0.2 h² + 0.05 h³ falls through zero once on [0, 1]
  const std::array<double, 4> g = {0.3, -1.0, -0.2, 0.05};
  const PolynomialRoots<8> poly(g.data(), 3, 100.0);
  const double root = poly.root(0, 0.0, 1.0, true);
  EXPECT_LE(poly.value(0, root), 0.0);
  const HeldProblem reference = [&] {
    HeldProblem held;
    std::copy(g.begin(), g.end(), held.p.begin());
    held.problem.degree = 3;
    held.problem.lo = 0.0;
    held.problem.hi = 1.0;
    return held;
  }();
  const double exact = static_cast<double>(precise_root(reference));
  EXPECT_LE(std::fabs(root - exact), 4 * std::numeric_limits<double>::epsilon() * 101.0);
}

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
