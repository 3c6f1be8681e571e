// The minimum-norm least-squares solution x of K x = b for a small symmetric
// positive semi-definite K (a collision matrix, possibly singular), by a
// complete orthogonal decomposition: where b is in K's range it solves
// K x = b exactly, with no component in K's null space. Compiled once
// (minimum_norm_solution.cpp) for the sizes the impulse law and the contact
// problem use, rather than in every unit that includes them.
#pragma once

#include <Eigen/Core>

namespace impactlab::rigidbody {

Eigen::Vector2d minimum_norm_solution(const Eigen::Matrix2d& k, const Eigen::Vector2d& b);
Eigen::Vector3d minimum_norm_solution(const Eigen::Matrix3d& k, const Eigen::Vector3d& b);

}  // namespace impactlab::rigidbody
