// The name nearest a misspelt one (nearest_name.hpp).
#include <impactlab/io/nearest_name.hpp>

#include <algorithm>
#include <cstddef>

namespace impactlab {

namespace {

// the optimal string alignment distance: Levenshtein's edits plus the swap
// of two neighbouring characters, each one edit
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t columns = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * columns);
  auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * columns + j]; };
  for (std::size_t i = 0; i <= a.size(); ++i) at(i, 0) = i;
  for (std::size_t j = 0; j <= b.size(); ++j) at(0, j) = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      at(i, j) = std::min({at(i - 1, j) + 1, at(i, j - 1) + 1, at(i - 1, j - 1) + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        at(i, j) = std::min(at(i, j), at(i - 2, j - 2) + 1);
    }
  return at(a.size(), b.size());
}

}  // namespace

std::optional<std::string> nearest_name(std::string_view name,
                                        const std::vector<std::string_view>& candidates) {
  std::optional<std::string> nearest;
  std::size_t best = 0;
  for (std::string_view candidate : candidates) {
    const std::size_t allowed =
        std::clamp<std::size_t>(std::max(name.size(), candidate.size()) / 3, 1, 3);
    const std::size_t distance = edit_distance(name, candidate);
    if (distance > allowed || (nearest && distance >= best)) continue;
    nearest = std::string(candidate);
    best = distance;
  }
  return nearest;
}

}  // namespace impactlab
