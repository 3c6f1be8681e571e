// The cross-product matrix: ã b = a × b, for writing the collision matrix of
// rigid bodies as matrix products (impulse lecture, slide 1).
//     ã = [  0   −a_z   a_y ]
//         [  a_z   0   −a_x ]
//         [ −a_y  a_x    0  ]
// In the plane, the matching object is the perpendicular ω × r = ω r⊥ with
// r⊥ = (−r_y, r_x) for a rotation ω about the axis out of the plane.
#pragma once

#include <Eigen/Core>

namespace impactlab::rigidbody {

inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

// r⊥ = ẑ × r (m): the velocity of the point r per unit angular velocity in 2D
inline Eigen::Vector2d perpendicular(const Eigen::Vector2d& r) { return {-r.y(), r.x()}; }

// the planar cross product r × J (its component out of the plane)
inline double cross2(const Eigen::Vector2d& r, const Eigen::Vector2d& j) {
  return r.x() * j.y() - r.y() * j.x();
}

}  // namespace impactlab::rigidbody
