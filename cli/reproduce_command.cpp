// `impactlab reproduce jin2003`: the paper's Fig. 4 under each impact model,
// data, sidecars, REPORT.md and PNGs in one directory
// (api/jin2003_reproduction.hpp, api/jin2003_report.hpp).
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <thread>

#include <fmt/format.h>

#include <impactlab/api/jin2003_report.hpp>
#include <impactlab/api/jin2003_reproduction.hpp>
#include <impactlab/api/model_spec.hpp>
#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "program_files.hpp"
#include "table_options.hpp"
#include <impactlab/platform/run_program.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

// The values as given; their defaults come from the "reproduce" option table.
struct ReproduceOptions {
  std::string paper;
  std::vector<std::string> assignments;
  std::vector<std::string> models;
  std::string out;
  int threads = 0;  // 0: all cores
  bool quick = false;
  bool no_plot = false;
  bool quiet = false;
};

// Draws the PNGs with the plot script of the source tree; a missing Python
// or matplotlib costs the pictures, never the data.
void draw_plots(const std::filesystem::path& directory, bool quiet) {
  const std::filesystem::path script =
      program_file("notebooks_data/jin2003/plot_jin2003.py");
  const std::filesystem::path python = plot_python();
  if (!std::filesystem::exists(script) || !std::filesystem::exists(python)) {
    std::cerr << "impactlab: warning: plots skipped (" << python.string() << " or "
              << script.string() << " not found); the data are complete\n";
    return;
  }
  // an argument vector, never shell text: the directory is data
  if (run_program({python.string(), script.string(), directory.string()},
                  quiet ? ProgramOutput::discard_stdout : ProgramOutput::inherit) != 0)
    std::cerr << "impactlab: warning: the plot script failed; the data are complete\n";
}

int run_reproduce(const ReproduceOptions& options, const std::vector<std::string>& command_line) {
  if (options.paper != "jin2003")
    throw BadInput("paper", options.paper, "the figure sets known are: jin2003");
  Scene scene = load_scene("jin2003");
  for (const auto& assignment : options.assignments) apply_override(scene, assignment);

  for (const auto& model : options.models) {
    Scene check = scene;
    apply_model(check, model);  // BadInput names an unknown model or key
  }

  Jin2003Settings settings;
  settings.models = options.models;
  settings.threads = options.threads > 0
                         ? options.threads
                         : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (options.quick) {
    // a coarse version for tests: the same pipeline, fewer values
    settings.omega_points = 21;
    settings.V0_points = 41;
    settings.periods = 300.0;
    settings.recorded_impacts = 40;
    settings.history_periods = 3.0;
  }
  const std::filesystem::path directory = options.out;
  // created now, so that a bad --out is refused before the run; removed again
  // if the run fails before its files are committed
  RunFiles run_files = open_run_files(directory);

  ProgressBar progress(!options.quiet);
  settings.progress = [&progress](double fraction) { progress.update(fraction); };
  const Jin2003Results results = reproduce_jin2003(scene, settings);

  std::string joined;
  for (const auto& word : command_line) joined += (joined.empty() ? "" : " ") + word;
  const nlohmann::json provenance = {{"impactlab_version", IMPACTLAB_VERSION},
                                     {"command", command_line},
                                     {"command_line", joined},
                                     {"created_utc", utc_now()},
                                     {"scene", scene_record(scene)},
                                     {"threads", settings.threads},
                                     {"quick", options.quick},
                                     {"source", "Jin, Hu & Bishop (2003), Acta Mechanica Sinica "
                                                "19(6), Fig. 4"}};
  write_jin2003_outputs(results, settings, scene, provenance, run_files);
  if (!options.no_plot) draw_plots(directory, options.quiet);
  if (!options.quiet)
    std::cout << fmt::format("jin2003: Fig. 4 reproduced in {:.1f} s on {} thread(s)\nwrote {}\n",
                             results.wall_time, settings.threads,
                             (directory / "REPORT.md").string());
  return exit_done;
}

}  // namespace

Command add_reproduce_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "reproduce", "reproduce a paper's figures (jin2003: Fig. 4 of Jin, Hu & Bishop 2003)");
  auto options = std::make_shared<ReproduceOptions>();
  TableOptions table(*command, "reproduce");
  table.add("paper", options->paper);
  table.add("set", options->assignments);
  table.add("models", options->models);
  table.add("out", options->out);
  table.add("threads", options->threads);
  table.add("quick", options->quick);
  table.add("no_plot", options->no_plot);
  table.add("quiet", options->quiet);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_reproduce(*options, command_line);
          },
          "reproduce"};
}

}  // namespace impactlab::cli
