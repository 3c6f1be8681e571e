// `impactlab compare SCENE --models newton,paper,rigid`: the same scene under
// each model, side by side. Writes compare_impacts.csv, compare_contacts.csv,
// compare_section.csv, summary.md, compare.json (the sidecar) and, when
// matplotlib can draw it, compare.png; all atomically, compare.json last.
// Every model runs before anything is written, so a model the scene rejects
// (exit 2) leaves no output.
#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

#include <impactlab/api/compare.hpp>
#include <impactlab/api/scene_jobs.hpp>
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

// The models to run: the listed ones, or every model the scene accepts.
std::vector<std::string> models_to_run(const Scene& scene, const std::string& list, bool quiet) {
  return models_to_compare(scene, list, [quiet](const BadInput& bad) {
    if (!quiet) std::cerr << "impactlab: compare: skipping " << bad.what() << '\n';
  });
}

int run_compare(const SceneOptions& options, const std::string& model_list,
                const std::vector<std::string>& command_line) {
  // each model listed reads its own keys: no warning for a key the scene's model does not read
  const Scene scene = options.load_for_several_models();
  const std::vector<std::string> models = models_to_run(scene, model_list, options.quiet);
  RunRequest request = options.request();
  const auto directory = options.output_directory();

  ProgressBar progress(!options.quiet);
  std::size_t done = 0;
  request.progress = [&](double fraction) {
    progress.update((static_cast<double>(done) + fraction) / static_cast<double>(models.size()));
  };
  // the models one by one, so that the bar moves across all of them
  Comparison comparison;
  for (const auto& model : models) {
    Comparison one = compare_models(scene, {model}, request);
    comparison.period = one.period;
    comparison.runs.push_back(std::move(one.runs.front()));
    ++done;
  }
  const nlohmann::json numbers = comparison_numbers(comparison);
  // the data files, summary.md and compare.json, committed together
  RunFiles run_files = open_run_files(directory);
  write_impacts_csv(run_files.add("compare_impacts.csv").stream(), comparison);
  write_contacts_csv(run_files.add("compare_contacts.csv").stream(), comparison);
  write_section_csv(run_files.add("compare_section.csv").stream(), comparison);
  run_files.add("summary.md").stream() << comparison_summary(comparison, numbers);

  std::vector<std::string> files = {"compare_impacts.csv", "compare_contacts.csv",
                                    "compare_section.csv", "summary.md", "compare.json"};

  nlohmann::json runs = nlohmann::json::object();
  for (const auto& run : comparison.runs)
    runs[run.model] = {{"scene", scene_record(run.scene)},
                       {"run",
                        {{"t0_s", run.output.t0},
                         {"t_end_s", run.output.t_end},
                         {"t_final_s", run.output.t_final},
                         {"termination", to_string(run.output.termination)}}},
                       {"counts",
                        {{"steps", run.output.steps},
                         {"rhs_evaluations", run.output.rhs_evaluations},
                         {"impacts", run.output.impacts},
                         {"contact_phases", run.output.contact_phases},
                         {"accumulations", run.output.accumulations},
                         {"section_points", run.output.samples.size()}}},
                       {"wall_time_s", run.output.wall_time},
                       {"derived", run.output.derived}};
  double wall_time = 0.0;
  for (const auto& run : comparison.runs) wall_time += run.output.wall_time;
  nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"scene", scene_record(scene)},
      {"models", models},
      {"runs", runs},
      {"numbers", numbers},
      {"wall_time_s", wall_time},
      {"columns",
       {{"compare_impacts.csv",
         {{"k", "impact index, matched by order"},
          {"t_<model>", "s"},
          {"wall_<model>", "+1 / -1"},
          {"qdot_before_<model>", "rad/s"},
          {"qdot_after_<model>", "rad/s"},
          {"normal_impulse_<model>", "N s"},
          {"tangential_velocity_<model>", "m/s, before the impact"},
          {"tangential_velocity_after_<model>", "m/s, empty where the model does not record it"}}},
        {"compare_contacts.csv",
         {{"t_start", "s"}, {"t_end", "s"}, {"duration", "s"}, {"friction_work", "J"}}},
        {"compare_section.csv",
         {{"t", "s, t0 + k T"}, {"q_<model>", "rad"}, {"qdot_<model>", "rad/s"}}}}},
      {"files", files},
  };
  write_json(run_files.add("compare.json"), meta);
  run_files.commit();

  // the picture, drawn from the committed data: its failure costs the picture
  // only; where it is drawn, compare.json is rewritten (atomically) to list it
  // an argument vector, never shell text: the directory is data
  const std::vector<std::string> plot = {
      plot_python().string(), program_file("scripts/plot_compare.py").string(),
      directory.string()};
  if (run_program(plot, ProgramOutput::discard) == 0) {
    files.insert(files.end() - 1, "compare.png");
    meta["files"] = files;
    AtomicFile listed(directory / "compare.json");
    write_json(listed, meta);
    listed.commit();
  } else {
    std::cerr << "impactlab: warning: compare.png not drawn (" << program_file("scripts/plot_compare.py").string()
              << " failed); the data are written\n";
  }

  if (!options.quiet) {
    for (const auto& run : comparison.runs)
      std::cout << fmt::format("{:>8}: {} impacts, {} contact phases, {}, {:.3f} s wall\n",
                               run.model, run.impacts.size(), run.contacts.size(),
                               to_string(run.output.termination), run.output.wall_time);
    std::cout << fmt::format("wrote {}\n", (directory / "summary.md").string());
  }
  for (const auto& run : comparison.runs)
    if (run.output.termination != Termination::completed) return exit_stopped_early;
  return exit_done;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "compare",
      "run a scene under several impact models; side-by-side CSV, plot and summary");
  auto options = std::make_shared<SceneOptions>();
  auto models = std::make_shared<std::string>();
  TableOptions table(*command, "compare");
  options->add_run(table);
  table.add("models", *models);
  return {command,
          [options, models](const std::vector<std::string>& command_line) {
            return run_compare(*options, *models, command_line);
          },
          "compare"};
}

}  // namespace impactlab::cli
