// A bad model section: reported as one line `FILE:LINE:COL: message`, where
// LINE and COL point at the offending character of the scene file (toml++'s
// source regions, plus the offset inside an expression string).
#pragma once

#include <cstdint>
#include <string>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

// Where a piece of a model section sits in its scene file (1-based line and column).
struct SourcePosition {
  std::string file;
  std::uint32_t line = 0;
  std::uint32_t column = 0;

  // the position `offset` characters further along the same line
  [[nodiscard]] SourcePosition advanced(std::size_t offset) const {
    return {file, line, column + static_cast<std::uint32_t>(offset)};
  }
  [[nodiscard]] std::string text() const {
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
};

// A BadInput (exit status 2) whose one line is `FILE:LINE:COL: message`.
class ModelFileError : public BadInput {
 public:
  ModelFileError(const SourcePosition& where, std::string key, const std::string& message)
      : BadInput(std::move(key), where.text(), message), line_(where.text() + ": " + message) {}

  [[nodiscard]] const char* what() const noexcept override { return line_.c_str(); }

 private:
  std::string line_;
};

}  // namespace impactlab
