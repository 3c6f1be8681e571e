// A rigid body in the plane: mass, scalar moment of inertia about its centre
// of mass, position, orientation angle, linear and angular velocity.
//
// A static body (the ground, a wall) has zero inverse mass and inverse
// inertia: impulses do not move it. Angular quantities are about the axis out
// of the plane (counter-clockwise positive).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <impactlab/rigidbody/cross_matrix.hpp>

namespace impactlab::rigidbody {

struct Body2D {
  double inverse_mass = 0.0;     // 1/m (1/kg), 0 for a static body
  double inverse_inertia = 0.0;  // 1/I about the centre of mass (1/(kg m²))
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // centre of mass (m)
  double angle = 0.0;                                  // orientation (rad)
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // of the centre (m/s)
  double angular_velocity = 0.0;                       // (rad/s)

  static Body2D dynamic(double mass, double inertia) {
    return Body2D{1.0 / mass, 1.0 / inertia};
  }
  static Body2D fixed() { return Body2D{}; }

  [[nodiscard]] bool is_static() const { return inverse_mass == 0.0 && inverse_inertia == 0.0; }

  // rotation from the body frame to the world frame
  [[nodiscard]] Eigen::Matrix2d rotation() const { return Eigen::Rotation2Dd(angle).toRotationMatrix(); }

  // world position of a point given in the body frame (m)
  [[nodiscard]] Eigen::Vector2d world_point(const Eigen::Vector2d& body_point) const {
    return position + rotation() * body_point;
  }

  // velocity of the material point at world offset r from the centre (m/s)
  [[nodiscard]] Eigen::Vector2d point_velocity(const Eigen::Vector2d& r) const {
    return velocity + angular_velocity * perpendicular(r);
  }

  // an impulse J (N s) applied at world offset r from the centre
  void apply_impulse(const Eigen::Vector2d& impulse, const Eigen::Vector2d& r) {
    velocity += inverse_mass * impulse;
    angular_velocity += inverse_inertia * cross2(r, impulse);
  }

  // kinetic energy (J); infinite-mass bodies contribute nothing
  [[nodiscard]] double kinetic_energy() const {
    const double linear = inverse_mass > 0.0 ? 0.5 * velocity.squaredNorm() / inverse_mass : 0.0;
    const double angular = inverse_inertia > 0.0
                               ? 0.5 * angular_velocity * angular_velocity / inverse_inertia
                               : 0.0;
    return linear + angular;
  }
};

}  // namespace impactlab::rigidbody
