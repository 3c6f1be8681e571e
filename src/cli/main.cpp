// The `impactlab` program: parses and validates the command line, calls the
// library, writes the outputs. Exit status: 0 done; 2 bad input (one line on
// stderr naming the key and the value); 3 the run stopped early on a physical
// diagnostic (Painlevé, no progress) — its outputs are complete and say so;
// 1 anything else.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "io/bad_input.hpp"
#include "io/builtin_scenes.hpp"
#include "io/oscillator_registry.hpp"
#include "io/output.hpp"
#include "io/scene.hpp"

namespace {

using namespace impactlab;

constexpr int exit_bad_input = 2;
constexpr int exit_stopped_early = 3;

// Validators: a finite number, a positive finite number (CLI11's own range
// checks let inf through and print the whole double range).
std::string check_number(const std::string& text, bool positive) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return "not a number: " + text;
  if (!std::isfinite(value)) return "not a finite number: " + text;
  if (positive && !(value > 0.0)) return "must be > 0: " + text;
  return {};
}
const CLI::Validator finite_number([](std::string& text) { return check_number(text, false); },
                                   "FINITE");
const CLI::Validator positive_number([](std::string& text) { return check_number(text, true); },
                                     "POSITIVE");

// Options shared by the subcommands that run a scene.
struct SceneOptions {
  std::string scene = "jin2003";
  std::vector<std::string> assignments;
  double t_end = 0.0;
  double periods = 0.0;
  std::string out;
  int threads = 1;
  bool quiet = false;

  void add_to(CLI::App& command) {
    command.add_option("scene", scene, "built-in scene name or path to a scene file (.toml)")
        ->capture_default_str();
    command.add_option("--set", assignments,
                       "KEY=VALUE, repeatable: a parameter (omega, V0, e_n, ...) or a dotted key "
                       "(initial.theta, integrator.rtol)");
    auto* t_end_option = command.add_option("--t-end", t_end, "end time (s)")
                             ->check(finite_number);
    command.add_option("--periods", periods, "forcing periods to run from t0 (default 100)")
        ->check(positive_number)
        ->excludes(t_end_option);
    command.add_option("--out", out, "output directory (default out/<scene>)");
    command.add_option("--threads", threads, "worker threads (a single run uses one)")
        ->check(CLI::Range(1, 1024));
    command.add_flag("--quiet", quiet, "print nothing but errors");
  }

  [[nodiscard]] Scene load() const {
    Scene loaded = load_scene(scene);
    for (const auto& assignment : assignments) apply_override(loaded, assignment);
    return loaded;
  }

  [[nodiscard]] RunRequest request() const {
    RunRequest request;
    if (t_end != 0.0) {
      request.periods = 0.0;
      request.t_end = t_end;
    } else {
      request.periods = periods > 0.0 ? periods : 100.0;
    }
    return request;
  }

  [[nodiscard]] std::filesystem::path output_directory() const {
    if (!out.empty()) return out;
    return std::filesystem::path("out") / std::filesystem::path(scene).stem();
  }
};

// A progress bar on stderr for runs long enough to want one (drawn only on a
// terminal, and only after the first half second).
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled && ::isatty(STDERR_FILENO)) {}
  ~ProgressBar() {
    if (drawn_) std::fputs("\n", stderr);
  }
  void update(double fraction) {
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

 private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

nlohmann::json scene_record(const Scene& scene) {
  const SceneSchema& schema = *oscillator_entry(scene.oscillator).schema;
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& spec : schema.keys) {
    const auto& value = scene.values.at(std::string(spec.key));
    nlohmann::json entry;
    if (const auto* number = std::get_if<double>(&value))
      entry["value"] = *number;
    else
      entry["value"] = std::get<std::string>(value);
    if (!spec.unit.empty()) entry["unit"] = spec.unit;
    parameters[std::string(spec.key)] = entry;
  }
  return {{"source", scene.name}, {"oscillator", scene.oscillator}, {"keys", parameters}};
}

int run_simulate(const SceneOptions& options, const std::vector<std::string>& command_line,
                 double sample_step) {
  const Scene scene = options.load();
  RunRequest request = options.request();
  request.sample_step = sample_step;
  const auto directory = options.output_directory();
  prepare_output_directory(directory);

  ProgressBar progress(!options.quiet);
  request.progress = [&progress](double fraction) { progress.update(fraction); };
  const RunOutput output = oscillator_entry(scene.oscillator).run(scene, request);

  const SceneSchema& schema = *oscillator_entry(scene.oscillator).schema;
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
          {"friction_work", "J, cumulative over contact phases since t0"}}},
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
  return 0;
}

int run_scenes(const std::string& name) {
  if (name.empty()) {
    for (const auto& builtin : builtin_scenes()) {
      const Scene scene = load_scene(builtin.name);
      std::cout << fmt::format("{:<16} {:<16} {}\n", builtin.name, scene.oscillator,
                               scene.text("description"));
    }
    return 0;
  }
  const Scene scene = load_scene(name);
  const SceneSchema& schema = *oscillator_entry(scene.oscillator).schema;
  std::cout << fmt::format("{} ({}): key = value [unit] range: help\n", name, scene.oscillator);
  for (const auto& spec : schema.keys) {
    const std::string value = to_text(scene.values.at(std::string(spec.key)));
    std::string range;
    if (spec.is_text) {
      for (auto choice : spec.choices) range += (range.empty() ? "" : "|") + std::string(choice);
    } else {
      range = fmt::format("{}{}, {}{}", spec.lower_open ? "(" : "[",
                          spec.lower <= -1e308 ? "-inf" : to_text(spec.lower),
                          spec.upper >= 1e308 ? "inf" : to_text(spec.upper),
                          spec.upper_open ? ")" : "]");
    }
    std::cout << fmt::format("  {:<20} = {:<12} {:<10} {:<14} {}\n", spec.key, value,
                             spec.unit.empty() ? "" : "[" + std::string(spec.unit) + "]", range,
                             spec.help);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"impactlab: event-driven simulation of impact oscillators", "impactlab"};
  app.set_version_flag("--version", std::string("impactlab ") + IMPACTLAB_VERSION);
  app.require_subcommand(1);

  std::string scenes_name;
  auto* scenes = app.add_subcommand("scenes", "list the built-in scenes, or one scene's keys");
  scenes->add_option("scene", scenes_name, "a scene whose keys, values, units and ranges to list");

  SceneOptions simulate_options;
  double sample_step = 0.0;
  auto* simulate = app.add_subcommand(
      "simulate", "run a scene; write events.csv and meta.json (and trajectory.csv with --sample)");
  simulate_options.add_to(*simulate);
  simulate->add_option("--sample", sample_step, "also write trajectory.csv sampled every DT s")
      ->check(positive_number);

  const std::vector<std::string> command_line(argv, argv + argc);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    std::cerr << "impactlab: " << error.what() << '\n';
    return exit_bad_input;
  }

  try {
    if (scenes->parsed()) return run_scenes(scenes_name);
    if (simulate->parsed()) return run_simulate(simulate_options, command_line, sample_step);
  } catch (const BadInput& bad) {
    std::cerr << "impactlab: " << bad.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& error) {
    std::cerr << "impactlab: error: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
