#include "command.hpp"
#include "table_options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include <unistd.h>

#include <fmt/format.h>

#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>
#include <impactlab/io/message_text.hpp>

namespace impactlab::cli {

namespace {

// CLI11 puts the validator's text after the option's name; the value is
// shortened so that the message stays one short line
std::string shown(const std::string& text) { return elide_value(text); }

std::string check_number(const std::string& text, bool positive) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return "not a number: " + shown(text);
  if (!std::isfinite(value)) return "not a finite number: " + shown(text);
  if (positive && !(value > 0.0)) return "must be > 0: " + shown(text);
  return {};
}

std::string check_number_in(const std::string& text, double lower, double upper) {
  if (auto error = check_number(text, false); !error.empty()) return error;
  const double value = std::strtod(text.c_str(), nullptr);
  if (value < lower || value > upper)
    return fmt::format("{} is outside [{}, {}]", shown(text), lower, upper);
  return {};
}

std::string check_count_in(const std::string& text, std::uint64_t lower, std::uint64_t upper) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    return "not a whole number >= 0: " + shown(text);
  if (value < lower || value > upper)
    return fmt::format("{} is outside [{}, {}]", shown(text), lower, upper);
  return {};
}

}  // namespace

const CLI::Validator& finite_number() {
  static const CLI::Validator validator(
      [](std::string& text) { return check_number(text, false); }, "FINITE");
  return validator;
}

const CLI::Validator& positive_number() {
  static const CLI::Validator validator(
      [](std::string& text) { return check_number(text, true); }, "POSITIVE");
  return validator;
}

CLI::Validator number_in(double lower, double upper) {
  return CLI::Validator(
      [lower, upper](std::string& text) { return check_number_in(text, lower, upper); },
      fmt::format("FINITE in [{}, {}]", lower, upper));
}

CLI::Validator count_in(std::uint64_t lower, std::uint64_t upper) {
  return CLI::Validator(
      [lower, upper](std::string& text) { return check_count_in(text, lower, upper); },
      fmt::format("WHOLE in [{}, {}]", lower, upper));
}

void SceneOptions::add_scene(TableOptions& table) {
  table.add("scene", scene);
  table.add("set", assignments);
  table.add("out", out);
  table.add("quiet", quiet);
}

void SceneOptions::add_run(TableOptions& table) {
  table.add("scene", scene);
  table.add("set", assignments);
  t_end_option = table.add("t_end", t_end);
  table.add("periods", periods);
  table.add("out", out);
  table.add("threads", threads);
  table.add("quiet", quiet);
}

Scene SceneOptions::load() const {
  Scene loaded = load_scene(scene);
  for (const auto& assignment : assignments) apply_override(loaded, assignment);
  return loaded;
}

RunRequest SceneOptions::request() const {
  RunRequest request;
  if (t_end_option != nullptr && t_end_option->count() > 0) {
    request.periods = 0.0;
    request.t_end = t_end;
  } else {
    request.periods = periods > 0.0 ? periods : 100.0;
  }
  return request;
}

std::filesystem::path SceneOptions::output_directory() const {
  if (!out.empty()) return out;
  return std::filesystem::path("out") / std::filesystem::path(scene).stem();
}

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled && ::isatty(STDERR_FILENO)) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\n", stderr);
}

void ProgressBar::update(double fraction) {
  if (!enabled_) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < 0.5) return;
  const int width = 40;
  const int filled = static_cast<int>(fraction * width);
  std::fprintf(stderr, "\r[%s%s] %3.0f%%  %.1f s", std::string(filled, '#').c_str(),
               std::string(width - filled, ' ').c_str(), 100.0 * fraction, elapsed);
  drawn_ = true;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

nlohmann::json scene_record(const Scene& scene) { return impactlab::scene_record(scene); }

}  // namespace impactlab::cli
