// `impactlab simulate`: one run of a scene; writes events.csv, meta.json and,
// with --sample, trajectory.csv, all atomically (meta.json last).
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include <impactlab/api/run_record.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "table_options.hpp"
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

int run_simulate(const SceneOptions& options, const std::vector<std::string>& command_line,
                 double sample_step) {
  const Scene scene = options.load();
  RunRequest request = options.request();
  request.sample_step = sample_step;
  const auto directory = options.output_directory();
  // the run's files, committed together at the end; the rows stream into
  // them as the run goes (memory does not grow with the run's length)
  RunFiles files = open_run_files(directory);
  std::vector<std::string> names = {"events.csv", "meta.json"};
  EventsCsvWriter events(files.add("events.csv"), event_extender(scene));
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
  TableOptions table(*command, "simulate");
  options->add_run(table);
  table.add("sample", *sample_step);
  return {command,
          [options, sample_step](const std::vector<std::string>& command_line) {
            return run_simulate(*options, command_line, *sample_step);
          },
          "simulate"};
}

}  // namespace impactlab::cli
