#include <impactlab/io/message_text.hpp>

#include <fmt/format.h>

namespace impactlab {

namespace {

constexpr std::size_t value_limit = 80;  // characters shown whole
constexpr std::size_t value_head = 24;   // characters kept before the cut
constexpr std::size_t value_tail = 48;   // and after it

}  // namespace

std::string escape_control_characters(std::string_view text) {
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

std::string elide_value(std::string_view value) {
  const std::string escaped = escape_control_characters(value);
  if (escaped.size() <= value_limit) return escaped;
  return fmt::format("{}...({} chars)...{}", escaped.substr(0, value_head), value.size(),
                     escaped.substr(escaped.size() - value_tail));
}

std::string one_line(std::string_view message) {
  const std::string escaped = escape_control_characters(message);
  if (escaped.size() <= message_limit) return escaped;
  return escaped.substr(0, message_limit - 3) + "...";
}

}  // namespace impactlab
