// A rigid body in space: mass, inertia tensor in the body frame, position,
// orientation (unit quaternion, body to world), velocity of the centre of
// mass and angular velocity in the world frame.
//
// The world-frame inverse inertia is R I_body⁻¹ Rᵀ. Between events the body
// is moved by `advance`: free motion under a constant force, with angular
// momentum L = I_world ω conserved (no torque), orientation by the quaternion
// kinematics of quaternion_kinematics.hpp with ω held over the step. That is
// exact while ω stays constant (a sphere, a spin about a principal axis) and
// first order in dt for a tumbling body.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <impactlab/rigidbody/quaternion_kinematics.hpp>

namespace impactlab::rigidbody {

struct Body3D {
  double inverse_mass = 0.0;                                        // 1/m (1/kg)
  Eigen::Matrix3d inverse_inertia_body = Eigen::Matrix3d::Zero();  // I_body⁻¹ (1/(kg m²))
  Eigen::Vector3d position = Eigen::Vector3d::Zero();              // centre of mass (m)
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body to world
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();              // (m/s)
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();      // world frame (rad/s)

  static Body3D dynamic(double mass, const Eigen::Matrix3d& inertia_body) {
    Body3D body;
    body.inverse_mass = 1.0 / mass;
    body.inverse_inertia_body = inertia_body.inverse();  // 3×3 SPD, constant: once per body
    return body;
  }
  // a solid sphere: I = (2/5) m R² on the diagonal
  static Body3D solid_sphere(double mass, double radius) {
    return dynamic(mass, Eigen::Matrix3d::Identity() * (0.4 * mass * radius * radius));
  }

  [[nodiscard]] Eigen::Matrix3d rotation() const { return orientation.toRotationMatrix(); }

  // I⁻¹ in the world frame (1/(kg m²))
  [[nodiscard]] Eigen::Matrix3d inverse_inertia_world() const {
    const Eigen::Matrix3d r = rotation();
    return r * inverse_inertia_body * r.transpose();
  }

  // velocity of the material point at world offset r from the centre (m/s)
  [[nodiscard]] Eigen::Vector3d point_velocity(const Eigen::Vector3d& r) const {
    return velocity + angular_velocity.cross(r);
  }

  // an impulse J (N s) applied at world offset r from the centre
  void apply_impulse(const Eigen::Vector3d& impulse, const Eigen::Vector3d& r) {
    velocity += inverse_mass * impulse;
    angular_velocity += inverse_inertia_world() * r.cross(impulse);
  }

  // free motion over dt (s) under a constant acceleration (m/s²), no torque:
  // the angular momentum is conserved, ω follows from it at the new attitude
  void advance(double dt, const Eigen::Vector3d& acceleration) {
    const Eigen::Vector3d momentum = inverse_inertia_world().inverse() * angular_velocity;
    position += velocity * dt + 0.5 * acceleration * dt * dt;
    velocity += acceleration * dt;
    orientation = rotate_by(orientation, angular_velocity, dt);
    angular_velocity = inverse_inertia_world() * momentum;
  }
};

}  // namespace impactlab::rigidbody
