// The linear solve behind floquet_algebra.hpp's `newton_step` for N > 2.
#include <impactlab/analysis/floquet_algebra.hpp>

#include <Eigen/LU>
#include <Eigen/QR>

namespace impactlab::detail {

bool dense_newton_step(const double* monodromy, const double* residual, std::size_t n,
                       double* step) {
  const auto size = static_cast<Eigen::Index>(n);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::MatrixXd matrix = Eigen::Map<const RowMajor>(monodromy, size, size) -
                                 Eigen::MatrixXd::Identity(size, size);
  if (!matrix.allFinite()) return false;
  const Eigen::VectorXd right = -Eigen::Map<const Eigen::VectorXd>(residual, size);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(matrix);
  if (lu.isInvertible()) {
    Eigen::Map<Eigen::VectorXd>(step, size) = lu.solve(right);
    return true;
  }
  // a family of orbits (M − I short of full rank): the least-squares step of least norm
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> family(matrix);
  if (family.rank() == 0) return false;
  const Eigen::VectorXd least_norm = family.solve(right);
  if (!least_norm.allFinite()) return false;
  Eigen::Map<Eigen::VectorXd>(step, size) = least_norm;
  return true;
}

}  // namespace impactlab::detail
