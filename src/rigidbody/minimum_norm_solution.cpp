#include <impactlab/rigidbody/minimum_norm_solution.hpp>

#include <Eigen/QR>

namespace impactlab::rigidbody {

Eigen::Vector2d minimum_norm_solution(const Eigen::Matrix2d& k, const Eigen::Vector2d& b) {
  return Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix2d>(k).solve(b);
}

Eigen::Vector3d minimum_norm_solution(const Eigen::Matrix3d& k, const Eigen::Vector3d& b) {
  return Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix3d>(k).solve(b);
}

}  // namespace impactlab::rigidbody
