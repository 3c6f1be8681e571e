#include "analysis/section.hpp"

#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "io/bad_input.hpp"

namespace impactlab {

SectionSpec parse_section(std::string_view text, std::string_view key) {
  const auto colon = text.find(':');
  const std::string_view kind = text.substr(0, colon);
  const std::string_view argument = colon == std::string_view::npos ? "" : text.substr(colon + 1);
  SectionSpec section;
  const auto bad = [&](std::string why) {
    return BadInput(std::string(key), std::string(text), std::move(why));
  };
  if (kind == "strobe") {
    section.kind = SectionKind::strobe;
    if (!argument.empty()) {
      const std::string number(argument);
      char* end = nullptr;
      section.phase = std::strtod(number.c_str(), &end);
      if (end == number.c_str() || *end != '\0' || !std::isfinite(section.phase))
        throw bad("the phase after strobe: must be a finite number (rad)");
      section.phase = std::fmod(section.phase, 2.0 * std::numbers::pi);
      if (section.phase < 0.0) section.phase += 2.0 * std::numbers::pi;
    }
    return section;
  }
  if (kind == "impact") {
    section.kind = SectionKind::impact;
    if (argument.empty() || argument == "0") return section;
    if (argument == "1" || argument == "+1") {
      section.wall = 1;
      return section;
    }
    if (argument == "-1") {
      section.wall = -1;
      return section;
    }
    throw bad("the wall after impact: must be +1, -1 or 0 (any wall)");
  }
  throw bad("expected strobe[:PHASE] or impact[:WALL]");
}

std::string to_string(const SectionSpec& section) {
  if (section.kind == SectionKind::strobe) return fmt::format("strobe:{}", section.phase);
  return fmt::format("impact:{}", section.wall);
}

}  // namespace impactlab
