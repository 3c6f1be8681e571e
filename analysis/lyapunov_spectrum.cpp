// The QR step and the running spread behind analysis/lyapunov_spectrum.hpp,
// on Eigen's dynamic-size Householder QR, compiled once for every N.
#include <impactlab/analysis/lyapunov_spectrum.hpp>

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

namespace impactlab {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace

LyapunovSpectrumAccumulator::LyapunovSpectrumAccumulator(std::size_t dimension, double period)
    : dimension_(dimension), period_(period), basis_(dimension * dimension),
      log_sums_(dimension, 0.0) {
  // the Q of [(1, …, 1)/√N, w_2, …, w_N]: orthonormal, its first column
  // ±(1, …, 1)/√N, the largest exponent's starting vector; the others from
  // w_j = e_j + sin((i + 1)(j + 1))/2, with no zero entry, so that no vector
  // starts inside a subspace that a Jacobian with a block structure (two
  // uncoupled oscillators) keeps to itself, where the QR could not turn it
  // towards a faster direction
  const auto size = static_cast<Eigen::Index>(dimension);
  Eigen::MatrixXd start(size, size);
  for (Eigen::Index i = 0; i < size; ++i)
    for (Eigen::Index j = 0; j < size; ++j)
      start(i, j) = (i == j ? 1.0 : 0.0) + 0.5 * std::sin(static_cast<double>((i + 1) * (j + 1)));
  start.col(0).setConstant(std::sqrt(1.0 / static_cast<double>(dimension)));
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(start);
  Eigen::Map<RowMajor>(basis_.data(), size, size) =
      qr.householderQ() * Eigen::MatrixXd::Identity(size, size);
}

bool LyapunovSpectrumAccumulator::advance(const double* jacobian, bool averaging) {
  const auto size = static_cast<Eigen::Index>(dimension_);
  Eigen::Map<RowMajor> basis(basis_.data(), size, size);
  const Eigen::MatrixXd stretched =
      Eigen::Map<const RowMajor>(jacobian, size, size) * Eigen::MatrixXd(basis);
  if (!stretched.allFinite()) return false;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(stretched);
  basis = qr.householderQ() * Eigen::MatrixXd::Identity(size, size);
  if (!averaging) return true;
  // |R_ii| against the round-off of the decomposition: the largest column
  // of J Q sets the scale (zero when the contact merged every state)
  const double scale = stretched.colwise().norm().maxCoeff();
  for (Eigen::Index i = 0; i < size; ++i) {
    const double stretch = std::fabs(qr.matrixQR()(i, i));
    log_sums_[static_cast<std::size_t>(i)] += stretch <= collapse_tolerance * scale
                                                  ? -std::numeric_limits<double>::infinity()
                                                  : std::log(stretch);
  }
  ++periods_averaged_;
  return true;
}

std::vector<double> LyapunovSpectrumAccumulator::exponents() const {
  std::vector<double> exponents(dimension_, std::numeric_limits<double>::quiet_NaN());
  if (periods_averaged_ == 0) return exponents;
  const double time = periods_averaged_ * period_;
  std::transform(log_sums_.begin(), log_sums_.end(), exponents.begin(),
                 [time](double sum) { return sum / time; });
  return exponents;
}

RunningSpread::RunningSpread(std::size_t dimension, int periods)
    : first_counted_(std::max(1, std::min(periods - 1, periods - periods / 4 + 1))),
      lowest_(dimension, std::numeric_limits<double>::infinity()),
      highest_(dimension, -std::numeric_limits<double>::infinity()) {}

void RunningSpread::add(int period, const std::vector<double>& running) {
  if (period < first_counted_) return;
  for (std::size_t i = 0; i < running.size(); ++i) {
    lowest_[i] = std::min(lowest_[i], running[i]);
    highest_[i] = std::max(highest_[i], running[i]);
  }
}

std::vector<double> RunningSpread::half_ranges(const std::vector<double>& final) const {
  std::vector<double> spread(final.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < final.size(); ++i) {
    if (final[i] == -std::numeric_limits<double>::infinity())
      spread[i] = 0.0;  // collapsed: exact
    else if (std::isfinite(lowest_[i]) && std::isfinite(highest_[i]))
      spread[i] = 0.5 * (highest_[i] - lowest_[i]);
  }
  return spread;
}

}  // namespace impactlab
