// `impactlab periodic`: a period-n orbit located by Newton shooting on the
// stroboscopic map with the saltation-corrected monodromy matrix, and its
// Floquet multipliers; writes periodic.json. n is given, or detected from the
// stroboscopic points after the transient (--period auto, the default).
// With --all, every orbit of the period that deflated Newton shooting finds
// from --starts states drawn from --box (api/periodic_job.hpp); writes
// orbits.csv beside periodic.json.
#include <cmath>
#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

#include <impactlab/analysis/periodic.hpp>
#include <impactlab/api/periodic_job.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "section_options.hpp"
#include "table_options.hpp"
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

// The values as given; their defaults come from the "periodic" option table.
struct PeriodicOptions {
  SceneOptions scene;
  PeriodicJob job;
};

void write_orbits_csv(AtomicFile& file, const std::vector<OrbitsColumn>& columns) {
  auto& out = file.stream();
  for (std::size_t c = 0; c < columns.size(); ++c) out << (c == 0 ? "" : ",") << columns[c].name;
  out << '\n';
  const std::size_t rows = columns.empty() ? 0 : columns.front().values.size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      out << (c == 0 ? "" : ",") << csv_field(columns[c].values[r]);
    out << '\n';
  }
}

// periodic.json: the run's record with what only a file has (the command,
// when, the wall time in s), put among the run's files
void write_periodic_json(RunFiles& run_files, nlohmann::json document,
                         const std::vector<std::string>& command_line, double wall_time) {
  document["command"] = command_line;
  document["created_utc"] = utc_now();
  document["wall_time_s"] = wall_time;
  write_json(run_files.add("periodic.json"), document);
}

int run_all_periodic(const PeriodicOptions& options, const Scene& scene,
                     const std::vector<std::string>& command_line) {
  const PeriodicOrbitsJobResult found = find_periodic_orbits(scene, options.job);
  const auto directory = options.scene.output_directory();
  RunFiles run_files = open_run_files(directory);
  write_orbits_csv(run_files.add("orbits.csv"), periodic_orbits_table(found));
  write_periodic_json(run_files, periodic_orbits_record(scene, found), command_line,
                      found.wall_time);
  run_files.commit();
  if (!options.scene.quiet) {
    const PeriodicOrbitsResult& result = found.result;
    int stable = 0;
    for (const auto& orbit : result.orbits) stable += orbit.stable ? 1 : 0;
    std::cout << fmt::format(
        "{}: {} orbits of period {} ({} stable) from {} starts: {} new, {} to a known orbit, {} "
        "not converged, {} stopped early\n",
        scene.name, result.orbits.size(), found.request.period, stable, found.request.starts,
        result.count(StartOutcome::new_orbit), result.count(StartOutcome::known_orbit),
        result.count(StartOutcome::not_converged), result.count(StartOutcome::stopped));
    std::cout << fmt::format("wrote {} and periodic.json\n", (directory / "orbits.csv").string());
  }
  return exit_done;
}

int run_periodic(const PeriodicOptions& options, const std::vector<std::string>& command_line) {
  const Scene scene = options.scene.load();
  if (options.job.all) return run_all_periodic(options, scene, command_line);
  const PeriodicJobResult found = find_periodic_orbit(scene, options.job);
  const auto directory = options.scene.output_directory();
  RunFiles run_files = open_run_files(directory);
  const PeriodicRequest& request = found.request;
  const PeriodicResult& result = found.result;
  write_periodic_json(run_files, periodic_record(scene, found), command_line, found.wall_time);
  run_files.commit();
  if (!options.scene.quiet) {
    std::string multipliers;
    for (const auto& multiplier : result.multipliers)
      multipliers += fmt::format("{}{:.9g}{:+.9g}i", multipliers.empty() ? "" : ", ",
                                 multiplier.real(), multiplier.imag());
    if (result.termination == Termination::no_tangent_map) multipliers = "none";
    if (result.converged)
      std::cout << fmt::format(
          "{}: period-{} orbit converged after {} iterations (residual {:.3g}); multipliers {}\n",
          scene.name, request.period, result.iterations, result.residual, multipliers);
    else
      std::cout << fmt::format("{}: period-{} orbit NOT converged after {} iterations (residual "
                               "{:.3g}): {}\n",
                               scene.name, request.period, result.iterations, result.residual,
                               result.failure);
    std::cout << fmt::format("wrote {}\n", (directory / "periodic.json").string());
  }
  // said even when quiet: where the search could not start well, and why
  if (!result.converged && found.period_source != "given")
    std::cerr << fmt::format("impactlab: warning: the period was {}; give one with --period N "
                             "(a sweep or poincare shows the attractor's)\n",
                             found.period_source);
  if (result.termination != Termination::completed)
    std::cerr << fmt::format("impactlab: run stopped early ({}) at the section time {} s{}\n",
                             to_string(result.termination), result.t_section,
                             result.termination == Termination::no_tangent_map
                                 ? ": an event of the orbit has no saltation matrix (an impulse "
                                   "on the friction cone's edge), so its multipliers do not exist"
                                 : "");
  return result.converged && result.termination == Termination::completed ? exit_done
                                                                         : exit_stopped_early;
}

}  // namespace

Command add_periodic_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "periodic", "locate a period-n orbit (Newton shooting) and its Floquet multipliers");
  auto options = std::make_shared<PeriodicOptions>();
  TableOptions table(*command, "periodic");
  options->scene.add_scene(table);
  table.add("period", options->job.period);
  table.add("phase", options->job.phase);
  table.add("transient", options->job.transient);
  table.add("max_iterations", options->job.max_iterations);
  table.add("tolerance", options->job.tolerance);
  table.add("all", options->job.all);
  table.add("starts", options->job.starts);
  table.add("box", options->job.box);
  table.add("seed", options->job.seed);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_periodic(*options, command_line);
          },
          "periodic"};
}

}  // namespace impactlab::cli
