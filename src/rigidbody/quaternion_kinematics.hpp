// Orientation of a 3D rigid body as a unit quaternion q (body frame to world
// frame), and its kinematics:
//     q̇ = ½ (0, ω) ⊗ q          ω: angular velocity in the world frame (rad/s)
// Over a step dt with ω held constant the exact update is a rotation by the
// angle |ω| dt about ω/|ω|: q ← exp(½ ω dt) ⊗ q. It keeps |q| = 1 up to
// round-off, which the update removes by normalising.
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace impactlab::rigidbody {

// q̇ (1/s) for world-frame angular velocity ω
inline Eigen::Quaterniond quaternion_rate(const Eigen::Quaterniond& q, const Eigen::Vector3d& omega) {
  const Eigen::Quaterniond w(0.0, omega.x(), omega.y(), omega.z());
  Eigen::Quaterniond rate = w * q;
  rate.coeffs() *= 0.5;
  return rate;
}

// q after dt (s) of rotation at constant world-frame ω (rad/s)
inline Eigen::Quaterniond rotate_by(const Eigen::Quaterniond& q, const Eigen::Vector3d& omega,
                                    double dt) {
  const double angle = omega.norm() * dt;
  if (angle == 0.0) return q;
  const Eigen::Quaterniond step(Eigen::AngleAxisd(angle, omega.normalized()));
  return (step * q).normalized();
}

}  // namespace impactlab::rigidbody
