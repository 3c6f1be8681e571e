// Text that goes into a one-line message on stderr: a value the user typed is
// shown with its control characters escaped (so that it cannot break the line)
// and, when long, shortened in the middle; a whole message is kept to one line
// of at most 200 characters.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace impactlab {

// Longest value shown whole in a message (characters).
constexpr std::size_t message_value_limit = 40;
// Longest message printed (characters, "impactlab: " included by the caller).
constexpr std::size_t message_limit = 188;

// Control characters as C escapes (\n, \t, \r, \xNN); everything else as is.
inline std::string escape_control_characters(std::string_view text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') escaped += "\\n";
    else if (c == '\r') escaped += "\\r";
    else if (c == '\t') escaped += "\\t";
    else if (byte < 0x20 || byte == 0x7f) escaped += fmt::format("\\x{:02x}", byte);
    else escaped += c;
  }
  return escaped;
}

// Keeps the first and last characters of a long text, with how many were left out.
inline std::string elide_middle(std::string_view text, std::size_t limit) {
  if (text.size() <= limit) return std::string(text);
  const std::size_t kept = limit / 2;
  return fmt::format("{}...({} chars)...{}", text.substr(0, kept), text.size(),
                     text.substr(text.size() - kept / 2));
}

// A value the user gave, as shown in a message.
inline std::string elide_value(std::string_view value) {
  return elide_middle(escape_control_characters(value), message_value_limit);
}

// A whole message: one line, at most message_limit characters.
inline std::string one_line(std::string_view message) {
  const std::string escaped = escape_control_characters(message);
  if (escaped.size() <= message_limit) return escaped;
  return escaped.substr(0, message_limit - 3) + "...";
}

}  // namespace impactlab
