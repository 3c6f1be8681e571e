// `impactlab simulate`: one run of a scene; writes events.csv, meta.json and,
// with --sample (or --plot), trajectory.csv, all atomically (meta.json last);
// with --plot, simulation.png (scripts/plot_simulation.py).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include <impactlab/api/run_record.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "program_files.hpp"
#include "table_options.hpp"
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>
#include <impactlab/platform/run_program.hpp>

namespace impactlab::cli {

namespace {

// The sampling of a run drawn without --sample: 64 samples per forcing
// period, at most 20 000 over the run (trajectory.csv stays small).
double plot_sample_step(const Scene& scene, const RunRequest& request) {
  if (!scene.values.contains("omega"))
    throw BadInput("plot", "(given)",
                   "give --sample DT as well: this scene has no forcing frequency omega to "
                   "sample the picture by");
  const double period = scene.forcing_period();
  const double span =
      request.periods > 0.0 ? request.periods * period : request.t_end - scene.number("t0");
  return std::max(period / 64.0, span / 20000.0);
}

int run_simulate(const SceneOptions& options, const std::vector<std::string>& command_line,
                 double sample_step, bool plot) {
  const Scene scene = options.load();
  RunRequest request = options.request();
  if (plot && sample_step == 0.0) sample_step = plot_sample_step(scene, request);
  request.sample_step = sample_step;
  const auto directory = options.output_directory();
  // the run's files, committed together at the end; the rows stream into
  // them as the run goes (memory does not grow with the run's length)
  RunFiles files = open_run_files(directory);
  std::vector<std::string> names = {"events.csv", "meta.json"};
  EventsCsvWriter events(files.add("events.csv"), event_extender(scene), event_columns(scene));
  request.keep_events = false;
  request.event_sink = &events;
  std::optional<TrajectoryCsvWriter> trajectory;
  if (sample_step > 0.0) {
    trajectory.emplace(files.add("trajectory.csv"));
    request.sample_sink = &*trajectory;
    names.push_back("trajectory.csv");
  }

  ProgressBar progress(!options.quiet);
  request.progress = [&progress](double fraction) { progress.update(fraction); };
  const RunOutput output = simulate(scene, request);

  // the run's record (api/run_record.hpp) with what only a file needs
  nlohmann::json meta = run_record(scene, output);
  meta["command"] = command_line;
  meta["created_utc"] = utc_now();
  meta["files"] = names;
  write_json(files.add("meta.json"), meta);
  // all files complete: put them in place together, meta.json last
  files.commit();

  const bool stopped = output.termination != Termination::completed;
  if (!options.quiet) {
    std::cout << fmt::format(
        "{}: t = {} .. {} s, {} impacts, {} contact phases, {} steps, {:.3f} s wall\n"
        "wrote {}\n",
        scene.name, output.t0, output.t_final, output.impacts, output.contact_phases,
        output.steps, output.wall_time, (directory / "meta.json").string());
  }
  // the picture, from the committed data: its failure costs the picture only
  if (plot) {
    const std::filesystem::path script = program_file("scripts/plot_simulation.py");
    if (run_program({plot_python().string(), script.string(), directory.string()},
                    ProgramOutput::discard) != 0)
      std::cerr << fmt::format(
          "impactlab: warning: simulation.png not drawn ({} {} failed: is matplotlib "
          "installed?); the data are in {}\n",
          plot_python().string(), script.string(), directory.string());
    else if (!options.quiet)
      std::cout << fmt::format("wrote {}\n", (directory / "simulation.png").string());
  }
  if (stopped) {
    const EventRecord* last = output.last_event ? &*output.last_event : nullptr;
    std::cerr << fmt::format("impactlab: run stopped early ({}) at t = {} s{}\n",
                             to_string(output.termination), output.t_final,
                             last ? fmt::format(", last event {} on wall {} at q = {}",
                                                to_string(last->kind), last->wall, last->q)
                                  : "");
    if (!output.stop_advice.empty()) std::cerr << "impactlab: " << output.stop_advice << '\n';
    return exit_stopped_early;
  }
  return exit_done;
}

}  // namespace

Command add_simulate_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "simulate",
      "run a scene; write events.csv and meta.json (and trajectory.csv with --sample)");
  auto options = std::make_shared<SceneOptions>();
  auto sample_step = std::make_shared<double>(0.0);
  auto plot = std::make_shared<bool>(false);
  TableOptions table(*command, "simulate");
  options->add_run(table);
  table.add("sample", *sample_step);
  table.add("plot", *plot);
  return {command,
          [options, sample_step, plot](const std::vector<std::string>& command_line) {
            return run_simulate(*options, command_line, *sample_step, *plot);
          },
          "simulate"};
}

}  // namespace impactlab::cli
