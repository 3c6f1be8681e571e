#include <impactlab/analysis/basin_measures.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include <impactlab/platform/not_a_number.hpp>

namespace impactlab {

namespace {

// −Σ p ln p of the labels of one box (nats)
double gibbs_entropy(const std::map<int, int>& counts, int total) {
  double entropy = 0.0;
  for (const auto& [label, count] : counts) {
    const double share = static_cast<double>(count) / total;
    entropy -= share * std::log(share);
  }
  return entropy;
}

// the share of points with a neighbour k points away (either axis, either
// side, inside the grid) of another label
double uncertain_fraction(const std::vector<int>& labels, int nx, int ny, int k) {
  const auto at = [&](int i, int j) { return labels[static_cast<std::size_t>(j) * nx + i]; };
  long uncertain = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int own = at(i, j);
      const bool differs = (i - k >= 0 && at(i - k, j) != own) ||
                           (i + k < nx && at(i + k, j) != own) ||
                           (j - k >= 0 && at(i, j - k) != own) ||
                           (j + k < ny && at(i, j + k) != own);
      if (differs) ++uncertain;
    }
  return static_cast<double>(uncertain) / (static_cast<double>(nx) * ny);
}

}  // namespace

BasinMeasures basin_measures(const std::vector<int>& labels, int nx, int ny, int box_size) {
  if (nx < 1 || ny < 1 || labels.size() != static_cast<std::size_t>(nx) * ny)
    throw std::invalid_argument("basin_measures: the labels are not an nx × ny grid");
  if (box_size < 1 || box_size > nx || box_size > ny)
    throw std::invalid_argument("basin_measures: box size " + std::to_string(box_size) +
                                " is not within 1 and the grid's shorter side " +
                                std::to_string(std::min(nx, ny)));
  BasinMeasures measures;
  measures.box_size = box_size;
  measures.labels = static_cast<int>(std::set<int>(labels.begin(), labels.end()).size());

  // basin entropy: the mean Gibbs entropy of the whole boxes
  double entropy_sum = 0.0, boundary_entropy_sum = 0.0;
  for (int box_j = 0; box_j + box_size <= ny; box_j += box_size)
    for (int box_i = 0; box_i + box_size <= nx; box_i += box_size) {
      std::map<int, int> counts;
      for (int j = box_j; j < box_j + box_size; ++j)
        for (int i = box_i; i < box_i + box_size; ++i)
          ++counts[labels[static_cast<std::size_t>(j) * nx + i]];
      const double entropy = gibbs_entropy(counts, box_size * box_size);
      ++measures.boxes;
      entropy_sum += entropy;
      if (counts.size() > 1) {
        ++measures.boundary_boxes;
        boundary_entropy_sum += entropy;
      }
    }
  measures.basin_entropy = entropy_sum / measures.boxes;
  measures.boundary_basin_entropy = measures.boundary_boxes > 0
                                        ? boundary_entropy_sum / measures.boundary_boxes
                                        : not_a_number;
  // above ln 2 by more than the rounding of the sums (a box split half and
  // half is ln 2 itself, not above it)
  measures.fractal_by_log2 = measures.boundary_boxes > 0 &&
                             measures.boundary_basin_entropy > std::log(2.0) * (1.0 + 1e-12);

  // uncertainty method: f(k) at k = 1, 2, 4, ... ≤ a quarter of the shorter side
  for (int k = 1; 4 * k <= std::min(nx, ny); k *= 2) {
    measures.scales.push_back(k);
    measures.uncertain_fraction.push_back(uncertain_fraction(labels, nx, ny, k));
  }
  // least squares of ln f = α ln k + c; f(1) = 0 means no boundary (and then
  // none at any scale: two labels k apart differ somewhere between)
  const std::size_t n = measures.scales.size();
  measures.uncertainty_exponent = not_a_number;
  measures.uncertainty_exponent_error = not_a_number;
  measures.boundary_dimension = not_a_number;
  bool all_positive = n >= 2;
  for (const double f : measures.uncertain_fraction) all_positive = all_positive && f > 0.0;
  if (!all_positive) return measures;
  double mean_x = 0.0, mean_y = 0.0;
  for (std::size_t s = 0; s < n; ++s) {
    mean_x += std::log(static_cast<double>(measures.scales[s])) / n;
    mean_y += std::log(measures.uncertain_fraction[s]) / n;
  }
  double sxx = 0.0, sxy = 0.0;
  for (std::size_t s = 0; s < n; ++s) {
    const double dx = std::log(static_cast<double>(measures.scales[s])) - mean_x;
    sxx += dx * dx;
    sxy += dx * (std::log(measures.uncertain_fraction[s]) - mean_y);
  }
  const double slope = sxy / sxx;
  measures.uncertainty_exponent = slope;
  measures.boundary_dimension = 2.0 - slope;
  if (n >= 3) {
    double residuals = 0.0;
    for (std::size_t s = 0; s < n; ++s) {
      const double x = std::log(static_cast<double>(measures.scales[s]));
      const double r = std::log(measures.uncertain_fraction[s]) - mean_y - slope * (x - mean_x);
      residuals += r * r;
    }
    measures.uncertainty_exponent_error = std::sqrt(residuals / (n - 2) / sxx);
  }
  return measures;
}

}  // namespace impactlab
