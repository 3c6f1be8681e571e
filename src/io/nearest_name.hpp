// The name nearest a misspelt one, for "did you mean ...?" in messages.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace impactlab {

// The candidate with the fewest single-character edits (insertions,
// deletions, substitutions and swaps of neighbours) from `name`, if it is
// within a third of the longer name's length (at least 1, at most 3 edits);
// the first such candidate on a tie. None where nothing is that close.
std::optional<std::string> nearest_name(std::string_view name,
                                        const std::vector<std::string_view>& candidates);

}  // namespace impactlab
