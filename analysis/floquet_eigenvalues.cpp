// The eigenvalues behind floquet_algebra.hpp's `eigenvalues` for N > 2.
#include <impactlab/analysis/floquet_algebra.hpp>

#include <limits>

#include <Eigen/Eigenvalues>

namespace impactlab::detail {

void dense_eigenvalues(const double* matrix, std::size_t n, std::complex<double>* values) {
  const auto size = static_cast<Eigen::Index>(n);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::MatrixXd m = Eigen::Map<const RowMajor>(matrix, size, size);
  const auto not_a_number = std::complex<double>(std::numeric_limits<double>::quiet_NaN(), 0.0);
  if (!m.allFinite()) {
    std::fill_n(values, n, not_a_number);
    return;
  }
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(m, false);
  if (solver.info() != Eigen::Success) {
    std::fill_n(values, n, not_a_number);
    return;
  }
  for (Eigen::Index i = 0; i < size; ++i) values[i] = solver.eigenvalues()[i];
  std::sort(values, values + n, [](const auto& a, const auto& b) {
    if (std::abs(a) != std::abs(b)) return std::abs(a) > std::abs(b);
    return a.imag() > b.imag();
  });
}

}  // namespace impactlab::detail
