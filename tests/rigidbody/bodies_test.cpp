// Rigid bodies, their collision matrices and the multi-contact solver:
// * quaternion kinematics: a constant spin turns a vector by |ω| t about ω;
// * a free sphere moves on the projectile parabola with its spin unchanged;
// * the collision matrix of a free body equals W M⁻¹ Wᵀ written in
//   generalized coordinates (x, y, θ), and the 3D formula reduces to the 2D
//   one for a planar contact;
// * a stack of boxes put down at rest stays at rest: no jitter or drift
//   beyond the stated bound 1e-9 m, 1e-9 m/s over 2 s of 5 ms steps (the
//   shock-propagation sweeps converge geometrically, factor 0.2 per sweep for
//   a square box, so 20 sweeps leave ~1e-14 of g dt);
// * a dropped stack comes to rest on the ground, boxes in order, no overlap
//   beyond the position correction's round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <impactlab/rigidbody/body2d.hpp>
#include <impactlab/rigidbody/body3d.hpp>
#include <impactlab/rigidbody/box_stack.hpp>
#include <impactlab/rigidbody/collision_matrix.hpp>
#include <impactlab/rigidbody/quaternion_kinematics.hpp>

namespace impactlab::rigidbody {
namespace IMPACTLAB_TEST_FILE_SCOPE {

TEST(QuaternionKinematics, ConstantSpinTurnsByAngleAboutAxis) {
  const Eigen::Vector3d omega(0.0, 0.0, 2.0);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int k = 0; k < 100; ++k) q = rotate_by(q, omega, 0.003);
  const Eigen::Vector3d turned = q * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(turned.x(), std::cos(0.6), 1e-13);
  EXPECT_NEAR(turned.y(), std::sin(0.6), 1e-13);
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
}

TEST(QuaternionKinematics, RateIsHalfOmegaTimesQ) {
  // q̇ = ½ (0, ω) ⊗ q against a central difference of the exact rotation
  const Eigen::Vector3d omega(0.3, -1.2, 0.7);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()));
  const double h = 1e-6;
  const Eigen::Quaterniond ahead = rotate_by(q, omega, h), behind = rotate_by(q, omega, -h);
  const Eigen::Vector4d difference = (ahead.coeffs() - behind.coeffs()) / (2.0 * h);
  EXPECT_LT((quaternion_rate(q, omega).coeffs() - difference).norm(), 1e-8);
}

TEST(Body3D, FreeSphereFollowsTheParabola) {
  Body3D ball = Body3D::solid_sphere(1.0, 0.1);
  ball.velocity = {1.0, 0.0, 3.0};
  ball.angular_velocity = {0.0, 5.0, 0.0};
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  for (int k = 0; k < 50; ++k) ball.advance(0.01, gravity);
  EXPECT_NEAR(ball.position.x(), 0.5, 1e-12);
  EXPECT_NEAR(ball.position.z(), 3.0 * 0.5 - 0.5 * 9.81 * 0.25, 1e-12);
  EXPECT_NEAR(ball.angular_velocity.y(), 5.0, 1e-12);
  // turned by 2.5 rad about y
  EXPECT_NEAR((ball.orientation * Eigen::Vector3d::UnitX()).z(), -std::sin(2.5), 1e-12);
}

TEST(CollisionMatrix, FreeBodyEqualsGeneralizedForm) {
  const double m = 3.0, I = 0.2;
  const Body2D body = Body2D::dynamic(m, I);
  const Eigen::Vector2d r(0.3, -0.4);
  const Eigen::Matrix2d K = collision_matrix(body, r, Body2D::fixed(), Eigen::Vector2d::Zero());
  // q = (x, y, θ): the contact point's velocity is W q̇ with W = [1 0 −r_y; 0 1 r_x]
  Eigen::Matrix3d M = Eigen::Vector3d(m, m, I).asDiagonal();
  Eigen::Matrix<double, 2, 3> W;
  W << 1.0, 0.0, -r.y(), 0.0, 1.0, r.x();
  const Eigen::Matrix2d generalized = collision_matrix<2, 3>(M, W);
  EXPECT_LT((K - generalized).norm(), 1e-14);
}

TEST(CollisionMatrix, SpatialFormulaReducesToPlanar) {
  const double m = 2.0, Izz = 0.15;
  Body3D a = Body3D::dynamic(m, Eigen::Vector3d(0.1, 0.2, Izz).asDiagonal());
  Body2D b = Body2D::dynamic(m, Izz);
  const Eigen::Vector3d r3(0.25, -0.1, 0.0);
  const Eigen::Matrix3d K3 = collision_matrix(a, r3, Body3D{}, Eigen::Vector3d::Zero());
  const Eigen::Matrix2d K2 =
      collision_matrix(b, r3.head<2>(), Body2D::fixed(), Eigen::Vector2d::Zero());
  EXPECT_LT((K3.topLeftCorner<2, 2>() - K2).norm(), 1e-14);
}

// bodies[0] the ground, boxes of half extents 0.1 × 0.1 stacked at rest
std::vector<Body2D> stack_at_rest(int boxes, double gap) {
  std::vector<Body2D> bodies{Body2D::fixed()};
  const double m = 1.0, I = m * (0.2 * 0.2 + 0.2 * 0.2) / 12.0;
  for (int k = 0; k < boxes; ++k) {
    Body2D box = Body2D::dynamic(m, I);
    box.position = {0.0, 0.1 + k * 0.2 + (k + 1) * gap};
    bodies.push_back(box);
  }
  return bodies;
}

BoxStackModel stack_model(int boxes) {
  BoxStackModel model;
  model.half_extents.assign(boxes, Eigen::Vector2d(0.1, 0.1));
  model.solver.e_n = 0.2;
  model.solver.mu = 0.5;
  return model;
}

TEST(BoxStack, StackAtRestStaysWithinTheStatedBound) {
  const int boxes = 6;
  const BoxStackModel model = stack_model(boxes);
  std::vector<Body2D> bodies = stack_at_rest(boxes, 0.0);
  const std::vector<Body2D> start = bodies;
  double worst_drift = 0.0, worst_speed = 0.0;
  for (int step = 0; step < 400; ++step) {
    const BoxStackStepReport report = box_stack_step(model, bodies, 0.005);
    ASSERT_EQ(report.contacts, static_cast<std::size_t>(2 * boxes));
    EXPECT_LE(report.shock.residual, 1e-12);
    for (int k = 1; k <= boxes; ++k) {
      worst_drift = std::max({worst_drift, (bodies[k].position - start[k].position).norm(),
                              std::fabs(bodies[k].angle)});
      worst_speed = std::max({worst_speed, bodies[k].velocity.norm(),
                              std::fabs(bodies[k].angular_velocity)});
    }
  }
  EXPECT_LE(worst_drift, 1e-9);
  EXPECT_LE(worst_speed, 1e-9);
}

TEST(BoxStack, ShockPropagationCarriesTheWeightThatContactSweepsLeave) {
  // one step from rest: the contact pass's sweeps pass the weight down one
  // box per sweep, so a tall stack keeps an approach residual; shock
  // propagation removes it
  const int boxes = 12;
  BoxStackModel model = stack_model(boxes);
  model.solver.contact_iterations = 5;
  std::vector<Body2D> bodies = stack_at_rest(boxes, 0.0);
  const BoxStackStepReport report = box_stack_step(model, bodies, 0.005);
  EXPECT_EQ(report.contact.sweeps, 5);
  EXPECT_GT(report.contact.residual, 1e-4);
  EXPECT_GT(report.shock.sweeps, boxes);
  EXPECT_LE(report.shock.residual, 1e-12);
}

TEST(BoxStack, DroppedStackComesToRest) {
  const int boxes = 4;
  const BoxStackModel model = stack_model(boxes);
  std::vector<Body2D> bodies = stack_at_rest(boxes, 0.02);
  for (int step = 0; step < 600; ++step) box_stack_step(model, bodies, 0.005);
  for (int k = 1; k <= boxes; ++k) {
    // resting on the one below: centre at 0.1 + 0.2 (k − 1), no overlap
    EXPECT_NEAR(bodies[k].position.y(), 0.1 + 0.2 * (k - 1), 1e-9) << "box " << k;
    EXPECT_LE(bodies[k].velocity.norm(), 1e-9) << "box " << k;
    EXPECT_NEAR(bodies[k].angle, 0.0, 1e-9);
  }
}

}  // namespace
}  // namespace impactlab::rigidbody
