// The acceleration-level contact problem (src/rigidbody/contact_phase.hpp)
// and the Painlevé rod (src/rigidbody/sliding_rod.hpp), against hand
// solutions:
// * a block on the floor pushed sideways: stick while |F| ≤ μ m g with
//   λ_T = −F, otherwise slide with γ̈_T = (F − μ s m g)/m; lifted off when
//   pulled up harder than its weight;
// * the rod sliding on a rough floor: λ_N = m (g − a sin θ θ̇²) /
//   (1 + 3cos²θ + 3 μ s sin θ cos θ) below the critical μ; above it (4/3 at
//   tan θ = 2) no solution when a_N < 0 and two when a_N > 0 — reported, and
//   in a simulation the run stops where the denominator vanishes.
#include <gtest/gtest.h>

#include <cmath>

#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/rigidbody/contact_phase.hpp>
#include <impactlab/rigidbody/sliding_rod.hpp>

namespace impactlab::rigidbody {
namespace IMPACTLAB_TEST_FILE_SCOPE {

GeneralizedContact<2> block(double m, double push, double lift) {
  GeneralizedContact<2> c;
  c.mass = Eigen::Matrix2d::Identity() * m;
  c.forces << push, lift - m * 9.81;
  c.jacobian << 0.0, 1.0, 1.0, 0.0;
  return c;
}

TEST(ContactPhase, BlockSticksInsideTheCone) {
  const double m = 2.0, mu = 0.5;
  const auto f = contact_forces<2>(block(m, 3.0, 0.0), mu, 0.0, 1e-12);
  EXPECT_EQ(f.regime, ContactRegime::stick);
  EXPECT_NEAR(f.normal, m * 9.81, 1e-12);
  EXPECT_NEAR(f.tangential, -3.0, 1e-12);
}

TEST(ContactPhase, BlockStartsSlidingOutsideTheCone) {
  const double m = 2.0, mu = 0.5, push = -15.0;  // |F| > μ m g = 9.81
  const auto c = block(m, push, 0.0);
  const auto f = contact_forces<2>(c, mu, 0.0, 1e-12);
  ASSERT_EQ(f.regime, ContactRegime::slide);
  EXPECT_EQ(f.slip_sign, -1.0);
  EXPECT_NEAR(f.normal, m * 9.81, 1e-12);
  EXPECT_NEAR(f.tangential, mu * m * 9.81, 1e-12);
  const Eigen::Vector2d qdd = c.acceleration({f.normal, f.tangential});
  EXPECT_NEAR(qdd(0), (push + mu * m * 9.81) / m, 1e-12);
  EXPECT_NEAR(qdd(1), 0.0, 1e-12);
}

TEST(ContactPhase, BlockSlidingKeepsKineticFriction) {
  const auto f = contact_forces<2>(block(1.0, 0.0, 0.0), 0.3, 0.7, 1e-12);
  EXPECT_EQ(f.regime, ContactRegime::slide);
  EXPECT_NEAR(f.tangential, -0.3 * 9.81, 1e-12);
}

TEST(ContactPhase, BlockPulledUpDetaches) {
  const auto f = contact_forces<2>(block(1.0, 2.0, 12.0), 0.3, 0.0, 1e-12);
  EXPECT_EQ(f.regime, ContactRegime::detached);
  EXPECT_EQ(f.normal, 0.0);
}

// the rod's hand formula: m A = 1 + 3cos²θ + 3 μ s sin θ cos θ
double rod_denominator(double theta, double mu, double s) {
  return 1.0 + 3.0 * std::pow(std::cos(theta), 2) + 3.0 * mu * s * std::sin(theta) * std::cos(theta);
}

SlidingRod::State rod_state(double theta, double theta_dot, double slip) {
  const double a = 0.5;
  return {0.0, a * std::sin(theta), theta, slip - a * std::sin(theta) * theta_dot,
          a * std::cos(theta) * theta_dot, theta_dot};
}

TEST(PainleveRod, BelowCriticalFrictionTheNormalForceIsTheHandFormula) {
  for (const double s : {1.0, -1.0}) {
    for (const double theta : {0.4, std::atan(2.0), 1.2}) {
      const SlidingRodParameters p{1.0, 0.5, 9.81, 1.2};
      const SlidingRod rod(p);
      const auto x = rod_state(theta, 1.5, 0.8 * s);
      const auto f = contact_forces<3>(rod.contact(x), p.mu, rod.slip(x), 1e-12);
      const double expected = p.m * (p.g - p.a * std::sin(theta) * 1.5 * 1.5) /
                              rod_denominator(theta, p.mu, s);
      ASSERT_EQ(f.regime, ContactRegime::slide) << "s " << s << " theta " << theta;
      EXPECT_NEAR(f.normal, expected, 1e-12 * expected);
      EXPECT_NEAR(f.tangential, -p.mu * s * expected, 1e-12 * expected);
    }
  }
}

TEST(PainleveRod, AboveCriticalFrictionNoSolutionIsReported) {
  const SlidingRodParameters p{1.0, 0.5, 9.81, 1.5};
  const SlidingRod rod(p);
  const double theta = std::atan(2.0);
  ASSERT_LT(rod_denominator(theta, p.mu, -1.0), 0.0);
  const auto x = rod_state(theta, 0.0, -0.5);  // a_N = −g < 0
  const auto f = contact_forces<3>(rod.contact(x), p.mu, rod.slip(x), 1e-12);
  EXPECT_EQ(f.regime, ContactRegime::painleve_no_solution);
  EXPECT_LT(f.denominator, 0.0);
}

TEST(PainleveRod, AboveCriticalFrictionTwoSolutionsAreReported) {
  const SlidingRodParameters p{1.0, 0.5, 9.81, 1.5};
  const SlidingRod rod(p);
  const double theta = std::atan(2.0);
  // a_N = −g + a sin θ θ̇² > 0 for θ̇² > g / (a sin θ)
  const double theta_dot = 1.1 * std::sqrt(p.g / (p.a * std::sin(theta)));
  const auto x = rod_state(theta, theta_dot, -0.5);
  const auto f = contact_forces<3>(rod.contact(x), p.mu, rod.slip(x), 1e-12);
  EXPECT_EQ(f.regime, ContactRegime::painleve_ambiguous);
}

// Samples of a run: the hand denominator m A for the slip sign, the lower
// end's height and the normal force, at every 1 ms.
struct RodSampler {
  const SlidingRod* rod;
  double mu;
  double next = 0.0;
  double min_denominator = INFINITY, min_height = INFINITY, min_force = INFINITY;
  [[nodiscard]] double next_time() const { return next; }
  void observe(double, const SlidingRod::State& x, SlidingRod::Mode) {
    next += 1e-3;
    const double s = rod->slip_sign(x);
    min_denominator = std::min(min_denominator, rod_denominator(x[2], mu, s));
    min_height = std::min(min_height, x[1] - 0.5 * std::sin(x[2]));
    const double a_n = -9.81 + 0.5 * std::sin(x[2]) * x[5] * x[5];
    min_force = std::min(min_force, -a_n / rod_denominator(x[2], mu, s));
  }
};

// The event loop carries the rod towards the Painlevé region (μ = 1.5 > 4/3):
// it never integrates through an inconsistent contact (m A > 0 and λ_N ≥ 0
// at every sample, the end never below the floor) and stops with the
// configuration classified.
TEST(PainleveRod, SimulationNeverIntegratesAnInconsistentContact) {
  const SlidingRodParameters p{1.0, 0.5, 9.81, 1.5};
  const SlidingRod rod(p);
  const double theta0 = 0.8;
  ASSERT_GT(rod_denominator(theta0, p.mu, -1.0), 0.0);
  const auto x0 = rod_state(theta0, 3.0, -1.0);
  StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = rod.max_step();
  EventLog log;
  OdeintDopri5<SlidingRod::State> stepper(settings);
  RodSampler sampler{&rod, p.mu};
  const auto result =
      simulate(rod, stepper, x0, SlidingRod::Mode::slide, 0.0, 2.0, LoopOptions{}, log, sampler);
  ASSERT_EQ(result.termination, Termination::stopped_by_model);
  EXPECT_GT(sampler.min_denominator, 0.0);
  EXPECT_GE(sampler.min_force, 0.0);
  EXPECT_GT(sampler.min_height, -1e-9);
  const EventRecord& last = log.records().back();
  EXPECT_TRUE(last.kind == EventKind::painleve || last.kind == EventKind::slip_reversal ||
              last.kind == EventKind::contact_end);
}

TEST(PainleveRod, BelowCriticalFrictionTheSameStartIsNoPainleve) {
  const SlidingRodParameters p{1.0, 0.5, 9.81, 1.2};  // μ < 4/3: m A > 0 for every θ
  const SlidingRod rod(p);
  const auto x0 = rod_state(0.8, 3.0, -1.0);
  StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = rod.max_step();
  EventLog log;
  OdeintDopri5<SlidingRod::State> stepper(settings);
  simulate(rod, stepper, x0, SlidingRod::Mode::slide, 0.0, 2.0, LoopOptions{}, log);
  EXPECT_EQ(log.count(EventKind::painleve), 0u);
}

}  // namespace
}  // namespace impactlab::rigidbody
