#include <impactlab/io/toml_nesting.hpp>

#include <memory>

#include <fmt/format.h>

namespace impactlab {

namespace {

// The cursor of the scan: where it is in the text, as line and column.
class TextCursor {
 public:
  explicit TextCursor(std::string_view text) : text_(text) {}

  [[nodiscard]] bool at_end() const { return index_ >= text_.size(); }
  [[nodiscard]] char peek() const { return text_[index_]; }
  [[nodiscard]] bool looking_at(std::string_view token) const {
    return text_.substr(index_, token.size()) == token;
  }
  void advance() {
    if (text_[index_] == '\n') {
      ++line_;
      column_ = 1;
    } else {
      ++column_;
    }
    ++index_;
  }
  void advance(std::size_t count) {
    for (std::size_t i = 0; i < count && !at_end(); ++i) advance();
  }
  [[nodiscard]] toml::source_position position() const {
    return {static_cast<toml::source_index>(line_), static_cast<toml::source_index>(column_)};
  }

 private:
  std::string_view text_;
  std::size_t index_ = 0;
  std::size_t line_ = 1, column_ = 1;
};

// Skips a string that starts at the cursor: "...", '...', """...""", '''...'''.
void skip_string(TextCursor& cursor) {
  const char quote = cursor.peek();
  const std::string triple(3, quote);
  const bool multiline = cursor.looking_at(triple);
  cursor.advance(multiline ? 3 : 1);
  while (!cursor.at_end()) {
    if (quote == '"' && cursor.peek() == '\\') {
      cursor.advance(2);
      continue;
    }
    if (multiline ? cursor.looking_at(triple) : cursor.peek() == quote) {
      cursor.advance(multiline ? 3 : 1);
      return;
    }
    if (!multiline && cursor.peek() == '\n') return;  // unterminated: toml++ reports it
    cursor.advance();
  }
}

}  // namespace

void check_toml_nesting(std::string_view text, const std::string& path) {
  const auto source = std::make_shared<const std::string>(path);
  auto refuse = [&](const std::string& message, const toml::source_position& where) {
    throw toml::parse_error(message.c_str(), where, source);
  };
  TextCursor cursor(text);
  std::size_t parts = 1;      // of the current run
  std::size_t depth = 0;      // of brackets
  toml::source_position run_start = cursor.position();
  while (!cursor.at_end()) {
    const char c = cursor.peek();
    if (c == '"' || c == '\'') {
      skip_string(cursor);
      continue;
    }
    if (c == '#') {
      while (!cursor.at_end() && cursor.peek() != '\n') cursor.advance();
      continue;
    }
    if (c == '.') {
      if (++parts > max_key_parts)
        refuse(fmt::format("a key of more than {} dotted parts", max_key_parts), run_start);
    } else if (c == '[' || c == '{') {
      if (++depth > max_bracket_depth)
        refuse(fmt::format("brackets nested more than {} deep", max_bracket_depth), cursor.position());
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
    const bool separator = c == '=' || c == ',' || c == '[' || c == ']' || c == '{' || c == '}' || c == '\n';
    cursor.advance();
    if (separator) {
      parts = 1;
      run_start = cursor.position();
    }
  }
}

toml::table parse_bounded_toml(std::string_view text, const std::string& path) {
  check_toml_nesting(text, path);
  return toml::parse(text, path);
}

}  // namespace impactlab
