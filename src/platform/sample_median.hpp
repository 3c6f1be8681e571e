// Medians of a sample of doubles (taken by value: they reorder it).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <impactlab/platform/not_a_number.hpp>

namespace impactlab {

// the middle value, the mean of the two middle values of an even count;
// NaN for an empty sample
inline double median(std::vector<double> values) {
  if (values.empty()) return not_a_number;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// the value at position n / 2 of the sorted sample, the upper of the two
// middle values of an even count: always one of the sample's own values;
// NaN for an empty sample
inline double upper_median(std::vector<double> values) {
  if (values.empty()) return not_a_number;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace impactlab
