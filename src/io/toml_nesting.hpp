// A bound on how deeply a TOML text nests, checked on the text before toml++
// parses it: toml++ builds (and destroys) one table per part of a dotted key
// by recursion, so a header of 100,000 dotted parts overflows the stack.
// Outside strings and comments, every run of text between the separators
// = , [ ] { } # and line breaks may hold at most `max_key_parts` parts
// (a float or a date has two at most), and brackets may nest at most
// `max_bracket_depth` deep.
#pragma once

#include <string>
#include <string_view>

#include <toml++/toml.h>

namespace impactlab {

inline constexpr std::size_t max_key_parts = 32;
inline constexpr std::size_t max_bracket_depth = 32;

// toml::parse_error at the first place the text nests deeper than the bounds
// (its line and column, `path` as its source), so that every reader reports
// it as it reports malformed TOML.
void check_toml_nesting(std::string_view text, const std::string& path);

// toml::parse after check_toml_nesting.
toml::table parse_bounded_toml(std::string_view text, const std::string& path);

}  // namespace impactlab
