#include <impactlab/analysis/basins.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace impactlab {

std::optional<std::array<double, 2>> canonical_point(const SweepRecord& record) {
  const int period = record.classification.period;
  const auto& points = record.result.points;
  if (period <= 0 || record.result.termination != SectionTermination::completed ||
      points.size() < static_cast<std::size_t>(period))
    return std::nullopt;
  std::optional<std::array<double, 2>> smallest;
  for (std::size_t k = points.size() - period; k < points.size(); ++k) {
    const std::array<double, 2> x{points[k].q, points[k].qdot};
    if (!smallest || x < *smallest) smallest = x;
  }
  return smallest;
}

BasinMap identify_attractors(const std::vector<const SweepRecord*>& records, double tolerance) {
  BasinMap map;
  map.attractor.reserve(records.size());
  for (const SweepRecord* record : records) {
    const auto point = canonical_point(*record);
    if (!point) {
      map.attractor.push_back(0);
      ++map.unclassified;
      continue;
    }
    const Classification& c = record->classification;
    const double scale = 1.0 + std::hypot((*point)[0], (*point)[1]);
    const auto same = std::find_if(map.attractors.begin(), map.attractors.end(),
                                   [&](const Attractor& a) {
                                     return a.period == c.period && a.contact == c.contact &&
                                            std::fabs(a.impacts_per_period - c.impacts_per_period) <=
                                                1e-9 * (1.0 + a.impacts_per_period) &&
                                            std::hypot(a.point[0] - (*point)[0],
                                                       a.point[1] - (*point)[1]) <=
                                                tolerance * scale;
                                   });
    if (same != map.attractors.end()) {
      ++same->basin_points;
      map.attractor.push_back(same->id);
      continue;
    }
    Attractor attractor;
    attractor.id = static_cast<int>(map.attractors.size()) + 1;
    attractor.period = c.period;
    attractor.impacts_per_period = c.impacts_per_period;
    attractor.contact = c.contact;
    attractor.point = *point;
    attractor.basin_points = 1;
    map.attractors.push_back(attractor);
    map.attractor.push_back(attractor.id);
  }
  return map;
}

}  // namespace impactlab
