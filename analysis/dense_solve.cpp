#include <impactlab/analysis/dense_solve.hpp>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace impactlab {

Eigen::VectorXd full_pivot_lu_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return a.fullPivLu().solve(b);
}

Eigen::VectorXd last_right_singular_vector(const Eigen::MatrixXd& a) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  return svd.matrixV().col(a.cols() - 1);
}

}  // namespace impactlab
