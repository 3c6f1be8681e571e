#include "command.hpp"
#include "table_options.hpp"

#include <cstdio>
#include <ctime>
#include <iostream>

#include <unistd.h>


#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>
#include <impactlab/io/message_text.hpp>

namespace impactlab::cli {

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
  Scene loaded = load_for_several_models();
  const std::vector<std::string> set_keys(loaded.assigned.begin(), loaded.assigned.end());
  for (const std::string& warning : unread_key_warnings(loaded, scene_schema(loaded), set_keys))
    std::cerr << "impactlab: warning: " << one_line(warning) << '\n';
  return loaded;
}

Scene SceneOptions::load_for_several_models() const {
  Scene loaded = load_scene(scene);
  for (const auto& assignment : assignments) apply_override(loaded, assignment);
  return loaded;
}

RunRequest SceneOptions::request() const {
  RunRequest request;
  if (option_given(t_end_option)) {
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

}  // namespace impactlab::cli
