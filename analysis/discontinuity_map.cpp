#include <impactlab/analysis/discontinuity_map.hpp>

#include <cmath>
#include <cstddef>

#include <Eigen/Core>

#include <impactlab/analysis/eigen_vector_conversions.hpp>

namespace impactlab {

namespace {

bool finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

Eigen::MatrixXd matrix(const MonodromyMatrix& m, std::size_t n) {
  Eigen::MatrixXd a(n, n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) a(i, j) = m.at(i).at(j);
  return a;
}

}  // namespace

DiscontinuityMap discontinuity_map(const GrazingTouch& local) {
  DiscontinuityMap map;
  const std::size_t n = local.state.size();
  const auto fail = [&](const std::string& why) {
    map.failure = why;
    return map;
  };
  if (n == 0 || local.gap_gradient.size() != n || local.rate_gradient.size() != n ||
      local.reset_jacobian.size() != n || local.field_jacobian.size() != n)
    return fail("the local data do not match the state's dimension");
  map.state = local.state;
  map.gap_gradient = local.gap_gradient;
  map.gap_acceleration = local.gap_acceleration;
  map.gap_jerk = local.gap_jerk;
  const double a = local.gap_acceleration;
  if (!(a > 0.0))
    return fail("the gap's second derivative at the touch is not positive (a = " +
                std::to_string(a) + "): the flight does not curve away from the wall");

  // u: ∇h·u = 0, ∇ḣ·u = 1, of least norm (unique for N = 2)
  Eigen::MatrixXd rows(2, n);
  rows.row(0) = to_eigen(local.gap_gradient).transpose();
  rows.row(1) = to_eigen(local.rate_gradient).transpose();
  const Eigen::Matrix2d gram = rows * rows.transpose();
  const double determinant = gram(0, 0) * gram(1, 1) - gram(0, 1) * gram(1, 0);
  if (!(determinant > 1e-14 * gram(0, 0) * gram(1, 1)))
    return fail("the gap's gradient and its rate's gradient are parallel at the touch");
  // the second column of the Gram matrix's inverse picks ∇ḣ·u = 1
  const Eigen::Vector2d coefficients(-gram(0, 1) / determinant, gram(0, 0) / determinant);
  const Eigen::VectorXd u = rows.transpose() * coefficients;

  const Eigen::MatrixXd g = matrix(local.reset_jacobian, n);
  const Eigen::MatrixXd j = matrix(local.field_jacobian, n);
  const Eigen::VectorXd w = (g - Eigen::MatrixXd::Identity(n, n)) * u;
  const Eigen::VectorXd leading = -std::sqrt(2.0 * a) * w;
  const Eigen::VectorXd next = 2.0 * j * w - (2.0 * local.gap_jerk / (3.0 * a)) * w;
  map.jump = to_values(w);
  map.leading = to_values(leading);
  map.next = to_values(next);
  if (!finite(map.jump) || !finite(map.next)) return fail("the reset's jump is not finite");
  map.available = true;
  return map;
}

std::vector<double> discontinuity_jump(const DiscontinuityMap& map,
                                       const std::vector<double>& deviation, bool next_order,
                                       double gap_offset) {
  std::vector<double> jump(map.leading.size(), 0.0);
  double h = gap_offset;
  for (std::size_t i = 0; i < deviation.size() && i < map.gap_gradient.size(); ++i)
    h += map.gap_gradient[i] * deviation[i];
  if (!(h < 0.0)) return jump;
  const double root = std::sqrt(-h);
  for (std::size_t i = 0; i < jump.size(); ++i)
    jump[i] = map.leading[i] * root + (next_order ? map.next[i] * h : 0.0);
  return jump;
}

}  // namespace impactlab
