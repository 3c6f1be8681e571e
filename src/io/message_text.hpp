// Text that goes into a one-line message on stderr: a value the user typed is
// shown with its control characters escaped (so that it cannot break the line)
// and, when long, shortened in the middle; a whole message is kept to one line
// of at most message_limit characters.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace impactlab {

// Longest message printed (characters; "impactlab: " and the newline come on top: 199 bytes in all).
constexpr std::size_t message_limit = 187;

// Control characters as C escapes (\n, \t, \r, \xNN); everything else as is.
std::string escape_control_characters(std::string_view text);

// A value the user gave, as shown in a message: escaped, and beyond 80
// characters its first 24 and last 48 kept around "...(N chars)..." (the end
// of a long path names the file).
std::string elide_value(std::string_view value);

// A whole message: one line, at most message_limit characters.
std::string one_line(std::string_view message);

}  // namespace impactlab
