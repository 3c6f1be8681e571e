// What every subcommand of the `impactlab` program shares: the exit statuses,
// the options of a command that runs a scene, a progress bar, and the
// provenance written beside every output.
//
// A subcommand lives in its own cli/<name>_command.cpp and exposes one
// `Command add_<name>_command(CLI::App&)`; main.cpp lists them.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include <impactlab/api/scene_record.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

// CLI11 itself is included only where the command line is parsed
// (main.cpp) and where options are made (table_options.cpp): a subcommand
// sees its nodes by name.
namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace impactlab::cli {

constexpr int exit_done = 0;
constexpr int exit_failed = 1;
constexpr int exit_bad_input = 2;
constexpr int exit_stopped_early = 3;
constexpr int exit_output_failed = 4;  // an output that cannot be written (OutputError)

// A registered subcommand: its CLI11 node, what runs when it was parsed, and
// the job whose option table (api/job_options.hpp) its options come from
// (empty: none). `run` receives the whole command line, for provenance.
struct Command {
  CLI::App* app;
  std::function<int(const std::vector<std::string>& command_line)> run;
  std::string_view job = {};
};

class TableOptions;

// Options shared by the subcommands that run a scene; their defaults, help
// and checks come from the job's option table.
struct SceneOptions {
  std::string scene;
  std::vector<std::string> assignments;
  double t_end = 0.0;
  double periods = 0.0;
  std::string out;
  int threads = 1;
  bool quiet = false;
  CLI::Option* t_end_option = nullptr;  // set by add_run: whether --t-end was given

  // the scene, --set, --out and --quiet
  void add_scene(TableOptions& table);
  // the scene, --set, the time span (--t-end, --periods), --out, --threads
  // and --quiet (simulate, compare)
  void add_run(TableOptions& table);
  // the scene with every --set applied (BadInput on a bad key or value), and
  // a warning line on stderr for each key set that the scene's model does not
  // read (api/model_keys.hpp)
  [[nodiscard]] Scene load() const;
  // the scene with every --set applied, without those warnings: for a command
  // that runs the models of its own list, each reading its own keys (compare)
  [[nodiscard]] Scene load_for_several_models() const;
  // the time span: --t-end T (an absolute end time, which must be after t0:
  // --t-end 0 with t0 = 0 is refused, not read as "not given"), else
  // --periods N from t0 (default 100); the two exclude each other
  [[nodiscard]] RunRequest request() const;
  // --out, else out/<scene>
  [[nodiscard]] std::filesystem::path output_directory() const;
};

// A progress bar on stderr for runs long enough to want one (drawn only on a
// terminal, and only after the first half second).
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  void update(double fraction);

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Current UTC time, ISO 8601 (for created_utc in meta files).
std::string utc_now();

}  // namespace impactlab::cli
