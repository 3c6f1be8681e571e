// The Newton–Coulomb impulse (src/rigidbody/newton_coulomb_impulse.hpp)
// against closed forms solved by hand in this file:
// * a solid sphere hitting the ground, with and without spin, sticking and
//   sliding: K = diag(7/(2m), 7/(2m), 1/m) gives the impulses in one line each;
// * a rod striking the ground at an angle: the 2×2 impulse equations solved by
//   Cramer's rule here, and the angular momentum about the contact point,
//   which no impulse through that point can change;
// * the 1-DOF pendulum, whose K has rank one: Model N's impact law and normal
//   impulse, no blind inverse (finite results, the stick case only where the
//   velocity change lies in the range of K);
// * the impulsive Painlevé case nᵀK(n − μt) ≤ 0, reported and not divided by.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Core>

#include <impactlab/rigidbody/body2d.hpp>
#include <impactlab/rigidbody/body3d.hpp>
#include <impactlab/rigidbody/collision_matrix.hpp>
#include <impactlab/rigidbody/generalized_system.hpp>
#include <impactlab/rigidbody/newton_coulomb_impulse.hpp>

namespace impactlab::rigidbody {
namespace IMPACTLAB_TEST_FILE_SCOPE {

// ---------------------------------------------------------------- sphere

struct SphereCase {
  const char* name;
  double vx, vz, spin_y, e_n, mu;
};

class SphereOnGround : public ::testing::TestWithParam<SphereCase> {};

TEST_P(SphereOnGround, ImpulseMatchesClosedForm) {
  const SphereCase c = GetParam();
  const double m = 2.0, R = 0.1, I = 0.4 * m * R * R;
  Body3D ball = Body3D::solid_sphere(m, R);
  ball.velocity = {c.vx, 0.0, c.vz};
  ball.angular_velocity = {0.0, c.spin_y, 0.0};
  const Body3D ground;  // static
  const Eigen::Vector3d r(0.0, 0.0, -R);
  const Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();

  const Eigen::Matrix3d K = collision_matrix(ball, r, ground, Eigen::Vector3d::Zero());
  const auto result = newton_coulomb_impulse<3>(K, ball.point_velocity(r), normal, {c.e_n, c.mu, 0.0});

  // by hand: ω × r = (−R ω_y, 0, 0), so the slip is u_x = v_x − R ω_y; K is
  // diagonal with 1/m + R²/I = 7/(2m) tangentially and 1/m normally
  const double u_x = c.vx - R * c.spin_y;
  const double j_n = -(1.0 + c.e_n) * m * c.vz;
  const bool sticks = (2.0 / 7.0) * std::fabs(u_x) <= c.mu * (1.0 + c.e_n) * std::fabs(c.vz);
  const double j_x = sticks ? -(2.0 * m / 7.0) * u_x : -c.mu * j_n * (u_x > 0 ? 1.0 : -1.0);
  EXPECT_EQ(result.regime, sticks ? ImpulseRegime::stick : ImpulseRegime::slide);
  EXPECT_NEAR(result.impulse.z(), j_n, 1e-12 * std::fabs(j_n));
  EXPECT_NEAR(result.impulse.x(), j_x, 1e-12 * (std::fabs(j_x) + 1.0));
  EXPECT_NEAR(result.impulse.y(), 0.0, 1e-15);

  ball.apply_impulse(result.impulse, r);
  // by hand: v⁺ = v + J/m, ω_y⁺ = ω_y + (r × J)_y / I = ω_y − R J_x / I
  EXPECT_NEAR(ball.velocity.x(), c.vx + j_x / m, 1e-12);
  EXPECT_NEAR(ball.velocity.z(), -c.e_n * c.vz, 1e-12);
  EXPECT_NEAR(ball.angular_velocity.y(), c.spin_y - R * j_x / I, 1e-10);
  if (sticks) {
    EXPECT_NEAR(ball.point_velocity(r).x(), 0.0, 1e-12);
  } else {
    // the slip keeps its direction, reduced by μ(1+e)|v_z|(1 + mR²/I) = 7/2 μ(1+e)|v_z|
    const double slip_after = u_x - (u_x > 0 ? 1.0 : -1.0) * 3.5 * c.mu * (1.0 + c.e_n) * std::fabs(c.vz);
    EXPECT_NEAR(ball.point_velocity(r).x(), slip_after, 1e-12);
    EXPECT_GT(slip_after * u_x, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SphereOnGround,
    ::testing::Values(SphereCase{"NoSpinSticks", 1.0, -2.0, 0.0, 0.5, 0.5},
                    SphereCase{"NoSpinSlides", 3.0, -0.5, 0.0, 0.5, 0.2},
                    SphereCase{"SpinSticks", 0.0, -2.0, 20.0, 0.5, 0.5},
                    SphereCase{"SpinSlides", 0.0, -0.5, 40.0, 0.5, 0.2},
                    SphereCase{"TopspinAgainstMotionSlides", 1.0, -0.5, -40.0, 0.0, 0.3},
                    SphereCase{"RollingNeedsNoFriction", 1.0, -1.0, 10.0, 0.3, 0.0}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(SphereOnGround, SeparatingContactGetsNoImpulse) {
  const Eigen::Matrix3d K = Eigen::Vector3d(3.5, 3.5, 1.0).asDiagonal();
  const auto result = newton_coulomb_impulse<3>(K, Eigen::Vector3d(1.0, 0.0, 0.2),
                                                Eigen::Vector3d::UnitZ(), {0.5, 0.5, 0.0});
  EXPECT_EQ(result.regime, ImpulseRegime::separating);
  EXPECT_EQ(result.impulse.norm(), 0.0);
}

TEST(SphereOnGround, TangentialRestitutionInTheStickCase) {
  // K diagonal: the stick impulse sets u_t⁺ = −e_t u_t⁻ exactly
  const Eigen::Matrix3d K = Eigen::Vector3d(3.5, 3.5, 1.0).asDiagonal();
  const Eigen::Vector3d u(0.4, -0.3, -2.0);
  const auto result = newton_coulomb_impulse<3>(K, u, Eigen::Vector3d::UnitZ(), {0.5, 0.8, 0.25});
  ASSERT_EQ(result.regime, ImpulseRegime::stick);
  EXPECT_NEAR(result.velocity_after.x(), -0.25 * 0.4, 1e-14);
  EXPECT_NEAR(result.velocity_after.y(), 0.25 * 0.3, 1e-14);
  EXPECT_NEAR(result.velocity_after.z(), 1.0, 1e-14);
}

// ---------------------------------------------------------------- rod

struct RodCase {
  const char* name;
  double angle, vx, vy, omega, e_n, mu;
};

class RodOnGround : public ::testing::TestWithParam<RodCase> {};

TEST_P(RodOnGround, ImpulseMatchesHandSolution) {
  const RodCase c = GetParam();
  const double m = 1.5, a = 0.4, I = m * a * a / 3.0;  // rod of length 2a
  const double s = std::sin(c.angle), co = std::cos(c.angle);
  Body2D rod = Body2D::dynamic(m, I);
  rod.velocity = {c.vx, c.vy};
  rod.angular_velocity = c.omega;
  const Eigen::Vector2d r(-a * co, -a * s);  // lower end, from the centre
  const Eigen::Matrix2d K = collision_matrix(rod, r, Body2D::fixed(), Eigen::Vector2d::Zero());
  const Eigen::Vector2d u = rod.point_velocity(r);
  const auto result = newton_coulomb_impulse<2>(K, u, Eigen::Vector2d::UnitY(), {c.e_n, c.mu, 0.0});

  // by hand: u = v + ω r⊥, r⊥ = (a sin α, −a cos α); K = I/m + r⊥ r⊥ᵀ / I
  const double ux = c.vx + c.omega * a * s, uy = c.vy - c.omega * a * co;
  const double kxx = 1.0 / m + a * a * s * s / I, kyy = 1.0 / m + a * a * co * co / I;
  const double kxy = -a * a * s * co / I;
  // stick: K J = (−u_x, −(1+e) u_y), Cramer's rule
  const double dx = -ux, dy = -(1.0 + c.e_n) * uy;
  const double det = kxx * kyy - kxy * kxy;
  const double jx_stick = (dx * kyy - kxy * dy) / det, jy_stick = (kxx * dy - kxy * dx) / det;
  const bool sticks = jy_stick >= 0.0 && std::fabs(jx_stick) <= c.mu * jy_stick;
  double jx = jx_stick, jy = jy_stick;
  if (!sticks) {
    const double sigma = ux > 0 ? 1.0 : -1.0;
    jy = -(1.0 + c.e_n) * uy / (kyy - c.mu * sigma * kxy);
    jx = -c.mu * sigma * jy;
  }
  EXPECT_EQ(result.regime, sticks ? ImpulseRegime::stick : ImpulseRegime::slide);
  EXPECT_NEAR(result.impulse.x(), jx, 1e-12 * (std::fabs(jx) + 1.0));
  EXPECT_NEAR(result.impulse.y(), jy, 1e-12 * (std::fabs(jy) + 1.0));

  // angular momentum about the contact point, L_P = I ω + m (−r) × v, is
  // unchanged by an impulse through that point
  const auto momentum_about_contact = [&](const Body2D& body) {
    return I * body.angular_velocity + m * cross2(-r, body.velocity);
  };
  const double before = momentum_about_contact(rod);
  rod.apply_impulse(result.impulse, r);
  EXPECT_NEAR(momentum_about_contact(rod), before, 1e-12);
  // Newton's law on the normal velocity; a stick leaves no slip
  EXPECT_NEAR(rod.point_velocity(r).y(), -c.e_n * uy, 1e-12);
  if (sticks) {
    EXPECT_NEAR(rod.point_velocity(r).x(), 0.0, 1e-12);
  }
  // an impact never adds energy (e_n ≤ 1, slip not reversed)
  EXPECT_LE(rod.kinetic_energy(),
            0.5 * m * (c.vx * c.vx + c.vy * c.vy) + 0.5 * I * c.omega * c.omega + 1e-12);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, RodOnGround,
    ::testing::Values(RodCase{"SteepFallSticks", 1.0, 0.2, -2.0, 0.0, 0.4, 0.8},
                    RodCase{"ShallowSlideSlides", 0.3, 2.0, -1.0, 0.0, 0.4, 0.3},
                    RodCase{"SpinningSlides", 0.6, 0.0, -1.0, 6.0, 0.2, 0.2},
                    RodCase{"Frictionless", 0.8, 1.0, -1.5, -2.0, 0.7, 0.0},
                    RodCase{"Plastic", 0.5, -0.5, -3.0, 1.0, 0.0, 0.5}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(RodOnGround, FrictionlessImpulseIsTheTextbookFormula) {
  // j = −(1+e) u_n / (1/m + (a cos α)² / I) for μ = 0
  const double m = 1.0, a = 0.5, I = m * a * a / 3.0, alpha = 0.7, e = 0.6;
  Body2D rod = Body2D::dynamic(m, I);
  rod.velocity = {0.0, -2.0};
  const Eigen::Vector2d r(-a * std::cos(alpha), -a * std::sin(alpha));
  const auto result = newton_coulomb_impulse<2>(
      collision_matrix(rod, r, Body2D::fixed(), Eigen::Vector2d::Zero()), rod.point_velocity(r),
      Eigen::Vector2d::UnitY(), {e, 0.0, 0.0});
  const double expected = (1.0 + e) * 2.0 / (1.0 / m + std::pow(a * std::cos(alpha), 2) / I);
  EXPECT_NEAR(result.normal_impulse, expected, 1e-12);
}

TEST(RodOnGround, WhereSlidingWouldBeInconsistentTheImpactSticks) {
  // K_yy − μ σ K_yx = (1 + 3cos²α + 3 μ σ sin α cos α)/m is negative for
  // σ = −1 above μ = 4/3 at tan α = 2; the stick impulse's ratio is then
  // |J_x|/J_y = (d_x K_yy + |K_xy| d_y)/(|K_xy| d_x + K_xx d_y) < K_yy/|K_xy| < μ
  // (because K_xx K_yy > K_xy²), so sticking is admissible and taken: the
  // impulse stays consistent
  const double m = 1.0, a = 0.5, I = m * a * a / 3.0, alpha = std::atan(2.0), mu = 1.5;
  Body2D rod = Body2D::dynamic(m, I);
  rod.velocity = {-5.0, -0.1};
  const Eigen::Vector2d r(-a * std::cos(alpha), -a * std::sin(alpha));
  const Eigen::Matrix2d K = collision_matrix(rod, r, Body2D::fixed(), Eigen::Vector2d::Zero());
  const double slide = K(1, 1) + mu * K(1, 0);
  EXPECT_NEAR(slide, (1.0 + 3.0 * std::pow(std::cos(alpha), 2) -
                      3.0 * mu * std::sin(alpha) * std::cos(alpha)) / m, 1e-12);
  ASSERT_LT(slide, 0.0);
  const auto result =
      newton_coulomb_impulse<2>(K, rod.point_velocity(r), Eigen::Vector2d::UnitY(), {0.5, mu, 0.0});
  EXPECT_EQ(result.regime, ImpulseRegime::stick);
  EXPECT_NEAR(result.velocity_after.x(), 0.0, 1e-12);
}

// ---------------------------------------------------------------- 1-DOF pendulum

// the right wall of the paper's pendulum: K = w wᵀ / (m l²) has rank one
GeneralizedContact<1> pendulum_contact(double pivot_velocity) {
  const double m = 0.5, l = 0.7, sin0 = 0.05 / 0.7, cos0 = std::sqrt(1.0 - sin0 * sin0);
  GeneralizedContact<1> c;
  c.mass << m * l * l;
  c.jacobian << -l * cos0, -l * sin0;
  c.velocity_offset << 0.0, pivot_velocity;
  return c;
}

TEST(PendulumImpulse, SingularCollisionMatrixGivesModelNLaw) {
  const double e_n = 0.3, mu = 0.6, qdot = 2.0;
  for (const double pivot : {0.9, -0.9, 0.05}) {
    const auto contact = pendulum_contact(pivot);
    ASSERT_LT(std::fabs(contact.collision_matrix().determinant()), 1e-15);
    const auto impact = generalized_impact<1>(contact, Eigen::Matrix<double, 1, 1>(qdot),
                                              {e_n, mu, 0.0});
    // Model N by hand: θ̇⁺ = −e_n θ̇⁻, P_N = −(1+e_n) M θ̇⁻ / (W_N − s μ W_T)
    const double w_n = contact.jacobian(0, 0), w_t = contact.jacobian(1, 0);
    const double gamma_t = pivot + w_t * qdot;
    const double s = gamma_t > 0 ? 1.0 : -1.0;
    const double p_n = -(1.0 + e_n) * contact.mass(0, 0) * qdot / (w_n - s * mu * w_t);
    EXPECT_EQ(impact.impulse.regime, ImpulseRegime::slide) << "pivot " << pivot;
    EXPECT_NEAR(impact.qdot_after(0), -e_n * qdot, 1e-14);
    EXPECT_NEAR(impact.impulse.normal_impulse, p_n, 1e-13);
    EXPECT_NEAR(impact.impulse.impulse(1), -s * mu * p_n, 1e-13);
    EXPECT_TRUE(impact.impulse.impulse.allFinite());
  }
}

TEST(PendulumImpulse, StickOnlyWhereTheVelocityChangeIsInTheRangeOfK) {
  // Δu = (−(1+e) u_n, −u_t) is parallel to w = (W_N, W_T) when
  // u_t = (1+e) u_n W_T / W_N: then sticking is possible, the minimum-norm
  // impulse is ∝ w, and |J_t| / J_n = tan θ0 < μ
  const double e_n = 0.3, mu = 0.6, qdot = 2.0;
  auto contact = pendulum_contact(0.0);
  const double w_n = contact.jacobian(0, 0), w_t = contact.jacobian(1, 0);
  const double u_n = w_n * qdot;
  const double u_t = (1.0 + e_n) * u_n * w_t / w_n;
  contact.velocity_offset(1) = u_t - w_t * qdot;
  const auto impact = generalized_impact<1>(contact, Eigen::Matrix<double, 1, 1>(qdot), {e_n, mu, 0.0});
  EXPECT_EQ(impact.impulse.regime, ImpulseRegime::stick);
  EXPECT_NEAR(impact.qdot_after(0), -e_n * qdot, 1e-13);
  EXPECT_NEAR(impact.impulse.velocity_after(1), 0.0, 1e-13);
  EXPECT_NEAR(impact.impulse.impulse(1) / impact.impulse.impulse(0), w_t / w_n, 1e-12);
}

TEST(PendulumImpulse, ImpulsivePainleveIsReportedNotDivided) {
  // μ tan θ0 > 1 with upward slip (s = +1): W_N − s μ W_T changes sign, so
  // nᵀK(n − μt) = W_N (W_N − μ W_T) / M < 0 and no sliding impulse exists;
  // the rank-one K admits no stick either
  const double mu = 15.0, qdot = 2.0;
  const auto contact = pendulum_contact(1.0);
  const double w_n = contact.jacobian(0, 0), w_t = contact.jacobian(1, 0);
  ASSERT_GT(mu * w_t / w_n, 1.0);  // μ tan θ0 > 1
  ASSERT_GT(contact.contact_velocity(Eigen::Matrix<double, 1, 1>(qdot))(1), 0.0);
  const auto impact = generalized_impact<1>(contact, Eigen::Matrix<double, 1, 1>(qdot), {0.3, mu, 0.0});
  EXPECT_EQ(impact.impulse.regime, ImpulseRegime::inconsistent);
  EXPECT_NEAR(impact.impulse.slide_denominator, w_n * (w_n - mu * w_t) / contact.mass(0, 0), 1e-12);
  EXPECT_EQ(impact.impulse.impulse.norm(), 0.0);
  EXPECT_TRUE(impact.qdot_after.allFinite());
}

}  // namespace
}  // namespace impactlab::rigidbody
