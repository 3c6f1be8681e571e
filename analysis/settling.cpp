#include <impactlab/analysis/settling.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace impactlab {

namespace {

// R² at or above which the logarithm of the mismatch falls on a line: a
// decay at one real multiplier, not the scatter of a chaotic motion
constexpr double straight_decay = 0.9;
// a spiral's envelope: the second half's largest mismatch at most this
// share of the first half's
constexpr double halving = 0.5;

// m_p(k) = |y_{k+p} − y_k| / scale for k = 0 … W − p − 1
std::vector<double> mismatches(const std::vector<SectionPoint>& window, int p, double scale) {
  std::vector<double> m;
  for (std::size_t k = 0; k + static_cast<std::size_t>(p) < window.size(); ++k)
    m.push_back(std::hypot(window[k + p].q - window[k].q, window[k + p].qdot - window[k].qdot) /
                scale);
  return m;
}

double largest(const std::vector<double>& m, std::size_t from, std::size_t to) {
  double most = 0.0;
  for (std::size_t k = from; k < to; ++k) most = std::max(most, m[k]);
  return most;
}

// whether log m(k) falls along k on a line: least squares with one slope and
// an intercept for each residue of k modulo `stride` (the points of a period-p
// orbit approach it each at its own distance), R² ≥ straight_decay
bool falls_on_a_line(const std::vector<double>& m, int stride) {
  const auto p = static_cast<std::size_t>(stride);
  double sum_kk = 0.0, sum_ky = 0.0, sum_yy = 0.0;
  for (std::size_t r = 0; r < p; ++r) {
    double n = 0.0, sum_k = 0.0, sum_y = 0.0, kk = 0.0, ky = 0.0, yy = 0.0;
    for (std::size_t k = r; k < m.size(); k += p) {
      // a mismatch of exactly 0 is a repeat to the last bit: no decay to fit
      if (!(m[k] > 0.0)) return false;
      const double x = static_cast<double>(k), y = std::log(m[k]);
      n += 1.0;
      sum_k += x;
      sum_y += y;
      kk += x * x;
      ky += x * y;
      yy += y * y;
    }
    if (n < 2.0) continue;
    sum_kk += kk - sum_k * sum_k / n;
    sum_ky += ky - sum_k * sum_y / n;
    sum_yy += yy - sum_y * sum_y / n;
  }
  if (!(sum_kk > 0.0) || !(sum_yy > 0.0)) return false;
  const double slope = sum_ky / sum_kk;
  return slope < 0.0 && sum_ky * sum_ky / (sum_kk * sum_yy) >= straight_decay;
}

}  // namespace

SettlingVerdict settling_verdict(const std::vector<SectionPoint>& window, int max_period,
                                 double tolerance) {
  const int longest = std::min<int>(max_period, static_cast<int>(window.size() / 2));
  if (longest < 1) return SettlingVerdict::not_periodic;
  double scale = 1.0;
  for (const SectionPoint& y : window) scale = std::max(scale, 1.0 + std::hypot(y.q, y.qdot));
  // the shortest period that repeats or still converges decides: points that
  // approach a period-2 orbit at the multiplier −0.9967 repeat after 4
  // periods to far better than after 2, but it is the 2 that converges
  for (int p = 1; p <= longest; ++p) {
    const std::vector<double> m = mismatches(window, p, scale);
    const std::size_t half = m.size() / 2;
    if (largest(m, 0, m.size()) <= tolerance) return SettlingVerdict::settled;
    if (falls_on_a_line(m, p) || largest(m, half, m.size()) <= halving * largest(m, 0, half))
      return SettlingVerdict::converging;
  }
  return SettlingVerdict::not_periodic;
}

}  // namespace impactlab
