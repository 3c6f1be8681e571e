// `impactlab simulate`: one run of a scene; writes events.csv, meta.json and,
// with --sample, trajectory.csv, all atomically (meta.json last).
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include "api/scene_jobs.hpp"
#include "api/scene_loading.hpp"
#include "cli/command.hpp"
#include "cli/commands.hpp"
#include "io/output.hpp"

namespace impactlab::cli {

namespace {

int run_simulate(const SceneOptions& options, const std::vector<std::string>& command_line,
                 double sample_step) {
  const Scene scene = options.load();
  RunRequest request = options.request();
  request.sample_step = sample_step;
  const auto directory = options.output_directory();
  prepare_output_directory(directory);

  ProgressBar progress(!options.quiet);
  request.progress = [&progress](double fraction) { progress.update(fraction); };
  const RunOutput output = simulate(scene, request);

  const SceneSchema& schema = scene_schema(scene);
  std::vector<std::string> files = {"events.csv", "meta.json"};
  AtomicFile events(directory / "events.csv");
  write_events_csv(events, output.events);
  std::optional<AtomicFile> trajectory;
  if (sample_step > 0.0) {
    trajectory.emplace(directory / "trajectory.csv");
    write_trajectory_csv(*trajectory, output.samples);
    files.push_back("trajectory.csv");
  }

  nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"scene", scene_record(scene)},
      {"model", scene.values.contains("model") ? to_text(scene.values.at("model")) : "newton"},
      {"integrator",
       {{"method", scene.text("integrator.method")},
        {"rtol", scene.number("integrator.rtol")},
        {"atol", scene.number("integrator.atol")}}},
      {"run",
       {{"t0_s", output.t0},
        {"t_end_s", output.t_end},
        {"t_final_s", output.t_final},
        {"termination", output.termination}}},
      {"counts",
       {{"steps", output.steps},
        {"rhs_evaluations", output.rhs_evaluations},
        {"impacts", output.impacts},
        {"contact_phases", output.contact_phases},
        {"accumulations", output.accumulations},
        {"grazings", output.grazings},
        {"events", output.events.size()}}},
      {"wall_time_s", output.wall_time},
      {"derived", output.derived},
      {"columns",
       {{"events.csv",
         {{"t", "s"},
          {"kind", "impact | grazing | accumulation | contact_start | contact_end | "
                   "slip_reversal | painleve"},
          {"wall", "+1 / -1, 0 for none"},
          {"q", std::string(schema.main_coordinate)},
          {"qdot_before", "d" + std::string(schema.main_coordinate) + "/dt before the event"},
          {"qdot_after", "d" + std::string(schema.main_coordinate) + "/dt after the event"},
          {"normal_impulse", "N s"},
          {"tangential_velocity", "m/s"},
          {"normal_force", "N"},
          {"friction_work", "J, cumulative over contact phases since t0"},
          {"instantaneous_residual",
           "m/s, pendulum Model P impacts: the paper's Eq. 26 residual (0: instantaneous)"},
          {"sliding_residual",
           "m/s, pendulum Model P impacts: the paper's Eqs. 21-22 residual (Fig. 4)"},
          {"tangential_velocity_after", "m/s, just after an impact (rigid model)"}}},
        {"trajectory.csv", {{"t", "s"}, {"q", std::string(schema.main_coordinate)},
                            {"qdot", "d" + std::string(schema.main_coordinate) + "/dt"},
                            {"mode", "mode of the hybrid system"}}}}},
      {"files", files},
  };
  AtomicFile meta_file(directory / "meta.json");
  write_json(meta_file, meta);

  // all files complete: put them in place, meta.json last
  events.commit();
  if (trajectory) trajectory->commit();
  meta_file.commit();

  const bool stopped = output.termination != "completed";
  if (!options.quiet) {
    std::cout << fmt::format(
        "{}: t = {} .. {} s, {} impacts, {} contact phases, {} steps, {:.3f} s wall\n"
        "wrote {}\n",
        scene.name, output.t0, output.t_final, output.impacts, output.contact_phases,
        output.steps, output.wall_time, (directory / "meta.json").string());
  }
  if (stopped) {
    const EventRecord* last = output.events.empty() ? nullptr : &output.events.back();
    std::cerr << fmt::format("impactlab: run stopped early ({}) at t = {} s{}\n",
                             output.termination, output.t_final,
                             last ? fmt::format(", last event {} on wall {} at q = {}",
                                                to_string(last->kind), last->wall, last->q)
                                  : "");
    return exit_stopped_early;
  }
  return exit_done;
}

}  // namespace

Command add_simulate_command(CLI::App& app) {
  auto* command = app.add_subcommand(
      "simulate", "run a scene; write events.csv and meta.json (and trajectory.csv with --sample)");
  auto options = std::make_shared<SceneOptions>();
  auto sample_step = std::make_shared<double>(0.0);
  options->add_to(*command);
  command->add_option("--sample", *sample_step, "also write trajectory.csv sampled every DT s")
      ->check(positive_number());
  return {command, [options, sample_step](const std::vector<std::string>& command_line) {
            return run_simulate(*options, command_line, *sample_step);
          }};
}

}  // namespace impactlab::cli
