#include <impactlab/analysis/floquet_multipliers.hpp>

#include <cmath>

#include <Eigen/Core>

#include <impactlab/analysis/dense_solve.hpp>
#include <impactlab/analysis/floquet_algebra.hpp>

namespace impactlab {

std::vector<std::complex<double>> multipliers_of(const MonodromyMatrix& m) {
  if (m.size() == 2) {
    const auto values = eigenvalues<2>({{{m[0][0], m[0][1]}, {m[1][0], m[1][1]}}});
    return {values.begin(), values.end()};
  }
  std::vector<double> rows;
  rows.reserve(m.size() * m.size());
  for (const auto& row : m) rows.insert(rows.end(), row.begin(), row.end());
  std::vector<std::complex<double>> values(m.size());
  detail::dense_eigenvalues(rows.data(), m.size(), values.data());
  return values;
}

std::vector<double> eigenvector_for(const MonodromyMatrix& m, double multiplier) {
  if (m.size() != 2) {
    // the right singular vector of M − λI of the smallest singular value
    const auto n = static_cast<Eigen::Index>(m.size());
    Eigen::MatrixXd a(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) a(i, j) = m[i][j];
    a.diagonal().array() -= multiplier;
    const Eigen::VectorXd v = last_right_singular_vector(a);
    return std::vector<double>(v.data(), v.data() + v.size());
  }
  // (M − λI) v = 0: v ⟂ the larger row of M − λI
  const double a = m[0][0] - multiplier, b = m[0][1];
  const double c = m[1][0], d = m[1][1] - multiplier;
  std::vector<double> v =
      std::hypot(a, b) >= std::hypot(c, d) ? std::vector<double>{-b, a} : std::vector<double>{-d, c};
  const double norm = std::hypot(v[0], v[1]);
  if (norm > 0.0) v = {v[0] / norm, v[1] / norm};
  return v;
}

}  // namespace impactlab
