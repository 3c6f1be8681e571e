#include <impactlab/analysis/attractor_following.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <impactlab/platform/not_a_number.hpp>

namespace impactlab {

namespace {

// the record's last `period` section points, from the canonical (the
// lexicographically smallest) one on, in time order
SectionPointSet cycle_of(const SweepRecord& record) {
  const int period = record.classification.period;
  const auto& points = record.result.points;
  SectionPointSet cycle;
  for (std::size_t k = points.size() - period; k < points.size(); ++k)
    cycle.push_back({points[k].q, points[k].qdot});
  std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
  return cycle;
}

// contact phases begun or ended per forcing period in the record window
double contact_phases_per_period(const SectionResult& result) {
  return result.periods_recorded > 0.0
             ? static_cast<double>(result.contact_phases) / result.periods_recorded
             : 0.0;
}

}  // namespace

double fraction_error(double fraction, int samples) {
  return samples > 0 ? std::sqrt(fraction * (1.0 - fraction) / static_cast<double>(samples))
                     : not_a_number;
}

AttractorsAtValue attractors_at_value(int index, double value,
                                      const std::vector<const SweepRecord*>& records,
                                      double tolerance) {
  const BasinMap map = identify_attractors(records, tolerance);
  AttractorsAtValue found;
  found.index = index;
  found.value = value;
  found.samples = static_cast<int>(records.size());
  found.unclassified = map.unclassified;
  found.sample_attractor = map.attractor;
  // each attractor from its first sample: its class, point and cycle
  std::vector<int> lyapunov_terms(map.attractors.size(), 0);
  for (const Attractor& a : map.attractors) {
    SampledAttractor sampled;
    sampled.period = a.period;
    sampled.impacts_per_period = a.impacts_per_period;
    sampled.impacts_per_cycle =
        static_cast<int>(std::lround(a.impacts_per_period * static_cast<double>(a.period)));
    sampled.contact = a.contact;
    sampled.point = a.point;
    sampled.min_impact_speed = not_a_number;
    sampled.lyapunov = 0.0;
    found.attractors.push_back(std::move(sampled));
  }
  for (std::size_t r = 0; r < records.size(); ++r) {
    const int local = map.attractor[r];
    if (local == 0) continue;
    SampledAttractor& a = found.attractors[local - 1];
    const SectionResult& result = records[r]->result;
    if (a.samples == 0) {
      a.cycle = cycle_of(*records[r]);
      a.contact_phases_per_period = contact_phases_per_period(result);
    }
    ++a.samples;
    // the smallest impact speed over every sample's record (NaN: no impact)
    if (std::isfinite(result.min_impact_speed) &&
        !(result.min_impact_speed >= a.min_impact_speed))
      a.min_impact_speed = result.min_impact_speed;
    // the exponent averaged over the samples that have one (−∞: rest on a wall)
    if (!std::isnan(result.lyapunov)) {
      a.lyapunov += result.lyapunov;
      ++lyapunov_terms[local - 1];
    }
  }
  for (std::size_t k = 0; k < found.attractors.size(); ++k) {
    SampledAttractor& a = found.attractors[k];
    a.lyapunov = lyapunov_terms[k] > 0 ? a.lyapunov / lyapunov_terms[k] : not_a_number;
    a.fraction = static_cast<double>(a.samples) / static_cast<double>(found.samples);
    a.fraction_error = fraction_error(a.fraction, found.samples);
  }
  return found;
}

double point_set_distance(const SectionPointSet& a, const SectionPointSet& b) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  double scale = 1.0;
  for (const SectionPointSet* set : {&a, &b})
    for (const auto& x : *set) scale = std::max(scale, 1.0 + std::hypot(x[0], x[1]));
  // the largest distance from a point of `from` to the nearest of `to`
  const auto directed = [](const SectionPointSet& from, const SectionPointSet& to) {
    double farthest = 0.0;
    for (const auto& x : from) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& y : to) nearest = std::min(nearest, std::hypot(x[0] - y[0], x[1] - y[1]));
      farthest = std::max(farthest, nearest);
    }
    return farthest;
  };
  return std::max(directed(a, b), directed(b, a)) / scale;
}

std::string_view to_string(AttractorChange change) {
  switch (change) {
    case AttractorChange::appear: return "appear";
    case AttractorChange::vanish: return "vanish";
    case AttractorChange::merge: return "merge";
    case AttractorChange::split: return "split";
  }
  return "appear";
}

std::vector<AttractorEvent> follow_attractors(std::vector<AttractorsAtValue>& values,
                                              double match_tolerance) {
  std::vector<AttractorEvent> events;
  int next_id = 1;
  for (std::size_t v = 0; v < values.size(); ++v) {
    auto& current = values[v].attractors;
    if (v == 0) {
      for (auto& a : current) a.id = next_id++;
      continue;
    }
    const auto& previous = values[v - 1].attractors;
    // every pair within the tolerance, the closest first (ties: old, then
    // new, in their order), and each side's nearest partner within it
    std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
    std::vector<int> nearest_new(previous.size(), -1), nearest_old(current.size(), -1);
    std::vector<double> nearest_new_distance(previous.size(), match_tolerance),
        nearest_old_distance(current.size(), match_tolerance);
    for (std::size_t i = 0; i < previous.size(); ++i)
      for (std::size_t j = 0; j < current.size(); ++j) {
        const double d = point_set_distance(previous[i].cycle, current[j].cycle);
        if (!(d <= match_tolerance)) continue;
        pairs.emplace_back(d, i, j);
        if (nearest_new[i] < 0 || d < nearest_new_distance[i]) {
          nearest_new[i] = static_cast<int>(j);
          nearest_new_distance[i] = d;
        }
        if (nearest_old[j] < 0 || d < nearest_old_distance[j]) {
          nearest_old[j] = static_cast<int>(i);
          nearest_old_distance[j] = d;
        }
      }
    std::sort(pairs.begin(), pairs.end());
    std::vector<bool> old_matched(previous.size(), false), new_matched(current.size(), false);
    for (const auto& [d, i, j] : pairs) {
      if (old_matched[i] || new_matched[j]) continue;
      old_matched[i] = new_matched[j] = true;
      current[j].id = previous[i].id;
    }
    // what is left over: births and splits numbered in the new value's order
    const int index = values[v].index;
    for (std::size_t j = 0; j < current.size(); ++j) {
      if (new_matched[j]) continue;
      current[j].id = next_id++;
      if (nearest_old[j] >= 0)
        events.push_back({AttractorChange::split, index, current[j].id,
                          previous[nearest_old[j]].id});
      else
        events.push_back({AttractorChange::appear, index, current[j].id, 0});
    }
    for (std::size_t i = 0; i < previous.size(); ++i) {
      if (old_matched[i]) continue;
      if (nearest_new[i] >= 0)
        events.push_back({AttractorChange::merge, index, previous[i].id,
                          current[nearest_new[i]].id});
      else
        events.push_back({AttractorChange::vanish, index, previous[i].id, 0});
    }
  }
  return events;
}

}  // namespace impactlab
