// `impactlab periodic`: a period-n orbit located by Newton shooting on the
// stroboscopic map with the saltation-corrected monodromy matrix, and its
// Floquet multipliers; writes periodic.json. n is given, or detected from the
// stroboscopic points after the transient (--period auto, the default).
#include <cmath>
#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

#include <impactlab/analysis/periodic.hpp>
#include <impactlab/api/periodic_job.hpp>
#include "command.hpp"
#include "commands.hpp"
#include "section_options.hpp"
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

struct PeriodicOptions {
  SceneOptions scene;
  std::string period = "auto";  // n, or auto: the period of the stroboscopic points
  double phase = 0.0;
  double transient = 100.0;
  int max_iterations = 30;
  double tolerance = 1e-11;
};

int run_periodic(const PeriodicOptions& options, const std::vector<std::string>& command_line) {
  const Scene scene = options.scene.load();
  PeriodicJob job;
  job.period = options.period;
  job.phase = options.phase;
  job.transient = options.transient;
  job.max_iterations = options.max_iterations;
  job.tolerance = options.tolerance;
  const PeriodicJobResult found = find_periodic_orbit(scene, job);
  const auto directory = options.scene.output_directory();
  RunFiles run_files(directory);
  const PeriodicRequest& request = found.request;
  const PeriodicResult& result = found.result;
  nlohmann::json document = periodic_record(scene, found);
  document["command"] = command_line;
  document["created_utc"] = utc_now();
  document["wall_time_s"] = found.wall_time;
  write_json(run_files.add("periodic.json"), document);
  run_files.commit();
  if (!options.scene.quiet) {
    std::string multipliers;
    for (const auto& multiplier : result.multipliers)
      multipliers += fmt::format("{}{:.9g}{:+.9g}i", multipliers.empty() ? "" : ", ",
                                 multiplier.real(), multiplier.imag());
    std::cout << fmt::format(
        "{}: period-{} orbit {} after {} iterations (residual {:.3g}); multipliers {}\nwrote {}\n",
        scene.name, request.period, result.converged ? "converged" : "NOT converged",
        result.iterations, result.residual, multipliers, (directory / "periodic.json").string());
  }
  if (result.termination != "completed")
    std::cerr << fmt::format("impactlab: run stopped early ({}) at the section time {} s\n",
                             result.termination, result.t_section);
  return result.converged ? exit_done : exit_stopped_early;
}

}  // namespace

Command add_periodic_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "periodic", "locate a period-n orbit (Newton shooting) and its Floquet multipliers");
  auto options = std::make_shared<PeriodicOptions>();
  command->add_option("scene", options->scene.scene, "built-in scene name or path")
      ->capture_default_str();
  command->add_option("--set", options->scene.assignments, "KEY=VALUE, repeatable");
  command->add_option("--out", options->scene.out, "output directory (default out/<scene>)");
  command->add_flag("--quiet", options->scene.quiet, "print nothing but errors");
  command->add_option("--period", options->period,
                      "n: the orbit's period in forcing periods, or auto (the period of the "
                      "stroboscopic points after the transient)")
      ->capture_default_str();
  command->add_option("--phase", options->phase, "section phase omega t mod 2 pi (rad)")
      ->check(number_in(0.0, 6.283185307179586))
      ->capture_default_str();
  command->add_option("--transient", options->transient, "forcing periods run first")
      ->check(number_in(0.0, 1e9))
      ->capture_default_str();
  command->add_option("--max-iterations", options->max_iterations, "Newton iterations")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--tolerance", options->tolerance, "relative residual")
      ->check(positive_number())
      ->capture_default_str();
  return {command, [options](const std::vector<std::string>& command_line) {
            return run_periodic(*options, command_line);
          }};
}

}  // namespace impactlab::cli
