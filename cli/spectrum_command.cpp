// `impactlab spectrum`: the amplitude spectrum of the main coordinate q(t)
// after a transient (FFTW), sampled over a whole number of forcing periods so
// that the harmonics kω/n of a period-n orbit fall on lines; writes
// spectrum.csv (omega,amplitude) and meta.json.
#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>

#include <fmt/format.h>

#include <impactlab/analysis/spectrum.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "table_options.hpp"
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

// The values as given; their defaults come from the "spectrum" option table.
struct SpectrumOptions {
  SceneOptions scene;
  double transient = 0.0;      // forcing periods discarded first
  int periods = 0;             // forcing periods analysed
  int samples_per_period = 0;
};

int run_spectrum(const SpectrumOptions& options, const std::vector<std::string>& command_line) {
  const Scene scene = options.scene.load();
  const double omega = scene.number("omega");
  const double period = 2.0 * std::numbers::pi / omega;
  RunRequest request;
  request.periods = options.transient + options.periods;
  request.sample_step = period / options.samples_per_period;
  request.keep_events = false;
  const auto directory = options.scene.output_directory();
  // spectrum.csv and meta.json, committed together; a run stopped early
  // leaves neither (nor a directory it created)
  RunFiles run_files = open_run_files(directory);
  ProgressBar progress(!options.scene.quiet);
  request.progress = [&progress](double fraction) { progress.update(fraction); };
  const RunOutput output = simulate(scene, request);

  // the samples of the last `periods` periods (the first index computed, not compared)
  const std::size_t wanted =
      static_cast<std::size_t>(options.periods) * static_cast<std::size_t>(options.samples_per_period);
  const std::size_t first =
      static_cast<std::size_t>(std::llround(options.transient * options.samples_per_period));
  if (output.termination != Termination::completed || output.samples.size() < first + wanted) {
    std::cerr << fmt::format("impactlab: run stopped early ({}) at t = {}; no spectrum written\n",
                             to_string(output.termination), output.t_final);
    return exit_stopped_early;
  }
  std::vector<double> q(wanted);
  for (std::size_t j = 0; j < wanted; ++j) q[j] = output.samples[first + j].q;
  const auto lines = amplitude_spectrum(q, request.sample_step);

  std::ofstream& csv = run_files.add("spectrum.csv").stream();
  csv << "omega,amplitude,harmonic\n";
  for (const auto& line : lines)
    csv << fmt::format("{},{},{}\n", line.angular_frequency, line.amplitude,
                                line.angular_frequency / omega);
  const SceneSchema& schema = scene_schema(scene);
  nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"scene", scene_record(scene)},
      {"spectrum",
       {{"transient_periods", options.transient},
        {"periods", options.periods},
        {"samples_per_period", options.samples_per_period},
        {"sample_interval", request.sample_step},
        {"window", "none (a whole number of forcing periods)"}}},
      {"counts", {{"samples", wanted}, {"lines", lines.size()}, {"impacts", output.impacts}}},
      {"wall_time_s", output.wall_time},
      {"columns",
       {{"omega", "angular frequency (rad per time unit)"},
        {"amplitude", "one-sided amplitude of " + std::string(schema.main_coordinate)},
        {"harmonic", "omega over the forcing frequency: a period-n orbit has lines at k/n"}}},
      {"files", {"spectrum.csv", "meta.json"}},
  };
  write_json(run_files.add("meta.json"), meta);
  run_files.commit();
  if (!options.scene.quiet)
    std::cout << fmt::format("{}: {} lines from {} samples\nwrote {}\n", scene.name, lines.size(),
                             wanted, (directory / "spectrum.csv").string());
  return exit_done;
}

}  // namespace

Command add_spectrum_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "spectrum", "amplitude spectrum of q(t) after a transient (FFTW); write spectrum.csv");
  auto options = std::make_shared<SpectrumOptions>();
  TableOptions table(*command, "spectrum");
  options->scene.add_scene(table);
  table.add("transient", options->transient);
  table.add("periods", options->periods);
  table.add("samples_per_period", options->samples_per_period);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_spectrum(*options, command_line);
          },
          "spectrum"};
}

}  // namespace impactlab::cli
