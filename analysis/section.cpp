#include <impactlab/analysis/section.hpp>

#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include <impactlab/io/bad_input.hpp>

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
  // user-given: q=LEVEL[:DIRECTION] or qdot=LEVEL[:DIRECTION]
  const auto equals = kind.find('=');
  const std::string_view variable = kind.substr(0, equals);
  if (equals != std::string_view::npos && (variable == "q" || variable == "qdot")) {
    section.kind = variable == "q" ? SectionKind::q_crossing : SectionKind::qdot_crossing;
    const std::string number(kind.substr(equals + 1));
    char* end = nullptr;
    section.level = std::strtod(number.c_str(), &end);
    if (end == number.c_str() || *end != '\0' || !std::isfinite(section.level))
      throw bad("the level after q= or qdot= must be a finite number");
    if (argument.empty() || argument == "up") section.direction = 1;
    else if (argument == "down") section.direction = -1;
    else if (argument == "both") section.direction = 0;
    else throw bad("the crossing direction must be up, down or both");
    return section;
  }
  throw bad("expected strobe[:PHASE], impact[:WALL], q=LEVEL[:up|down|both] or qdot=LEVEL[:...]");
}

std::string to_string(const SectionSpec& section) {
  if (section.kind == SectionKind::strobe) return fmt::format("strobe:{}", section.phase);
  if (section.kind == SectionKind::impact) return fmt::format("impact:{}", section.wall);
  const char* direction = section.direction > 0 ? "up" : section.direction < 0 ? "down" : "both";
  return fmt::format("{}={}:{}", section.kind == SectionKind::q_crossing ? "q" : "qdot",
                     section.level, direction);
}

void check_section_size(const SectionRequest& request, double omega, double max_step,
                        std::uint64_t step_budget) {
  const double period = 2.0 * std::numbers::pi / omega;
  if (!(std::isfinite(period) && period > 0.0))
    throw BadInput("omega", fmt::format("{}", omega),
                   fmt::format("the forcing period 2 pi/omega = {} is not a finite time", period));
  // a stroboscopic record is one period per point; an impact or crossing
  // record has no least length (it is bounded while it runs)
  const double record_periods =
      request.section.kind == SectionKind::strobe ? static_cast<double>(request.points) : 0.0;
  const double periods =
      (request.transient_impacts > 0 ? 0.0 : request.transient_periods) + record_periods;
  const double least_steps =
      std::isfinite(max_step) && max_step > 0.0 ? periods * period / max_step : 0.0;
  if (least_steps > static_cast<double>(step_budget)) {
    // name the larger of the two parts
    const bool transient_larger =
        request.transient_impacts == 0 && request.transient_periods > record_periods;
    throw BadInput(transient_larger ? "transient" : "points",
                   fmt::format("{}", transient_larger ? request.transient_periods : record_periods),
                   fmt::format("needs at least {:.3g} steps, over limits.max_steps = {} (raise "
                               "it with `set` limits.max_steps=N)",
                               least_steps, step_budget));
  }
}

}  // namespace impactlab
