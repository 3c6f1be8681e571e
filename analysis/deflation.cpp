#include <impactlab/analysis/deflation.hpp>

#include <cmath>
#include <cstddef>

namespace impactlab {

namespace {

// |x − r|² / ρ² over the tangent space
double squared_distance(const Deflation& deflation, std::span<const double> x,
                        const std::vector<double>& root) {
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (x[i] - root[i]) * (x[i] - root[i]);
  return sum / (deflation.radius * deflation.radius);
}

}  // namespace

double deflation_factor(const Deflation& deflation, std::span<const double> x) {
  double factor = 1.0;
  for (const auto& root : deflation.roots) {
    const double distance = std::sqrt(squared_distance(deflation, x, root));
    factor *= std::pow(distance, -deflation.power) + deflation.shift;
  }
  return factor;
}

void deflation_log_gradient(const Deflation& deflation, std::span<const double> x,
                            std::span<double> gradient) {
  for (double& g : gradient) g = 0.0;
  const double p = deflation.power;
  for (const auto& root : deflation.roots) {
    const double distance = std::sqrt(squared_distance(deflation, x, root));
    // −p |x − r|^(−p−2) / (|x − r|^(−p) + σ), times (x − r)
    const double scale = -p * std::pow(distance, -p - 2.0) /
                         (std::pow(distance, -p) + deflation.shift);
        for (std::size_t i = 0; i < x.size(); ++i)
      gradient[i] += scale * (x[i] - root[i]) / (deflation.radius * deflation.radius);
  }
}

bool deflate_step(const Deflation& deflation, std::span<const double> x, std::span<double> step) {
  if (deflation.roots.empty()) return true;
  std::vector<double> gradient(x.size());
  deflation_log_gradient(deflation, x, gradient);
  double along = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) along += gradient[i] * step[i];
  const double denominator = 1.0 - along;
  if (denominator == 0.0 || !std::isfinite(denominator)) return false;
  for (double& component : step) component /= denominator;
  return true;
}

}  // namespace impactlab
