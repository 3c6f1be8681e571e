// `impactlab bench`: work-precision data (cost against error) for every
// oscillator and stepper over a ladder of tolerances, the same curve for a
// SciPy solve_ivp event loop run in the same invocation, and the plots.
// Writes work_precision.csv and its sidecar work_precision.json (meta last),
// and <case>.png by scripts/plot_bench.py, into --out
// (default notebooks_data/bench).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <numbers>
#include <variant>

#include <fmt/format.h>

#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/work_precision.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "program_files.hpp"
#include "table_options.hpp"
#include <impactlab/platform/run_program.hpp>
#include <impactlab/integrate/stepper_names.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

// The values as given; their defaults come from the "bench" option table.
struct BenchOptions {
  std::string out;
  bool quick = false;
  bool scipy = true;  // --no-scipy turns it off
  bool plots = true;  // --no-plots turns it off
  int repetitions = 0;  // 0: 3, or 1 with --quick
  std::string python;
  bool quiet = false;
};

// One oscillator setting of the study.
struct BenchCase {
  std::string name;
  std::string scene;
  std::vector<std::string> assignments;  // --set KEY=VALUE on the built-in scene
  bool scipy;                            // also run the SciPy loop
};

// The study's sizes: full, or --quick (seconds, for the test suite).
struct BenchPlan {
  double timed_periods;       // forcing periods of each timed run
  double reference_periods;   // forcing periods the errors are measured over
  std::size_t max_reference_impacts;
  std::vector<double> rtols;  // impactlab's ladder; atol = atol_ratio · rtol
  double atol_ratio = 1e-2;
  std::vector<std::string> scipy_methods;
  std::vector<std::vector<double>> scipy_rtols;  // per SciPy method
  double long_run_periods;    // the 10^6-impact run (0: none)
};

// What a case needs beside its points.
struct CaseResult {
  BenchCase bench_case;
  Scene scene;
  double forcing_period = 0.0;  // s (or the oscillator's time unit)
  ReferenceImpacts reference;
  std::vector<WorkPrecisionPoint> points;
};

const std::vector<BenchCase>& bench_cases() {
  static const std::vector<BenchCase> cases = {
      {"jin2003_periodic", "jin2003", {}, true},
      {"jin2003_chattering", "jin2003", {"V0=4.163"}, false},
      {"linear_impact", "linear_impact", {}, true},
      {"bouncing_ball", "bouncing_ball", {}, true},
  };
  return cases;
}

BenchPlan plan_for(bool quick) {
  if (quick)
    return {50.0, 20.0, 20, {1e-6, 1e-8, 1e-10}, 1e-2, {"DOP853"}, {{1e-6, 1e-9}}, 0.0};
  return {2000.0,
          200.0,
          200,
          {1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13},
          1e-2,
          {"DOP853", "RK45"},
          {{1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12},
           {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9}},
          1e6};
}

// The bouncing ball's built-in scene is dropped from rest and chatters into
// riding every period; the bench starts it on its period-1 orbit instead
// (one impact per table period T: impact phase cos φ = gT(1 − r)/(2Aω(1 + r)),
// take-off speed gT/2), where a plain event loop such as SciPy's terminates.
void start_on_period_one_orbit(Scene& scene) {
  const double g = scene.number("g"), A = scene.number("A"), omega = scene.number("omega"),
               r = scene.number("r");
  const double period = 2.0 * std::numbers::pi / omega;
  const double phase = std::acos(g * period * (1.0 - r) / (2.0 * A * omega * (1.0 + r)));
  const double t0 = phase / omega;
  apply_override(scene, fmt::format("t0={:.17g}", t0));
  // on the table exactly as the scene computes it, z(t0) = A sin ωt0
  apply_override(scene, fmt::format("initial.y={:.17g}", A * std::sin(omega * t0)));
  apply_override(scene, fmt::format("initial.y_dot={:.17g}", 0.5 * g * period));
}

std::string number_text(double value) {
  return std::isfinite(value) ? fmt::format("{:.6g}", value) : "";
}

// the SciPy runs of every case that has them, through scripts/scipy_event_loop.py
void run_scipy(const BenchOptions& options, const BenchPlan& plan,
               std::vector<CaseResult>& results, const std::filesystem::path& directory,
               nlohmann::json& versions) {
  nlohmann::json spec = {{"quiet", options.quiet}, {"cases", nlohmann::json::array()}};
  for (const auto& result : results) {
    if (!result.bench_case.scipy) continue;
    nlohmann::json keys = nlohmann::json::object();
    for (const auto& [key, value] : result.scene.values)
      if (const auto* number = std::get_if<double>(&value)) keys[key] = *number;
    for (std::size_t m = 0; m < plan.scipy_methods.size(); ++m)
      spec["cases"].push_back({{"name", result.bench_case.name},
                               {"oscillator", result.scene.oscillator},
                               {"keys", keys},
                               {"t0", result.scene.number("t0")},
                               // half a period past the reference's window, so that an
                               // impact at its very end is not lost; max_impacts stops it
                               {"t_end", result.scene.number("t0") +
                                             (plan.reference_periods + 0.5) *
                                                 result.forcing_period},
                               {"max_impacts", result.reference.impacts.size()},
                               {"methods", {plan.scipy_methods[m]}},
                               {"rtols", plan.scipy_rtols[m]},
                               {"atol_ratio", plan.atol_ratio}});
  }
  const auto spec_path = directory / ".scipy_spec.json";
  const auto result_path = directory / ".scipy_result.json";
  {
    std::ofstream spec_file(spec_path);
    spec_file << spec.dump();
  }
  const std::string script = program_file("scripts/scipy_event_loop.py").string();
  // an argument vector, never shell text: paths are data
  const std::vector<std::string> command = {options.python, script, spec_path.string(),
                                            result_path.string()};
  const int status = run_program(command);
  std::filesystem::remove(spec_path);
  if (status != 0) {
    std::filesystem::remove(result_path);
    throw std::runtime_error("the SciPy event loop failed: " + describe_program(command));
  }
  nlohmann::json scipy_result;
  {
    std::ifstream result_file(result_path);
    scipy_result = nlohmann::json::parse(result_file);
  }
  std::filesystem::remove(result_path);
  versions = scipy_result["versions"];

  for (const auto& point : scipy_result["points"]) {
    for (auto& result : results) {
      if (result.bench_case.name != point["case"].get<std::string>()) continue;
      std::vector<ImpactSample> impacts;
      for (const auto& impact : point["impacts"]) impacts.push_back({impact[0], impact[1]});
      WorkPrecisionPoint measured;
      measured.tool = "scipy";
      measured.method = point["method"];
      measured.rtol = point["rtol"];
      measured.atol = point["atol"];
      measured.impacts = impacts.size();
      const double per_impact = impacts.empty() ? NAN : 1.0 / static_cast<double>(impacts.size());
      measured.seconds_per_impact = point["cpu_s"].get<double>() * per_impact;
      measured.wall_seconds_per_impact = point["wall_s"].get<double>() * per_impact;
      measured.rhs_per_impact = point["nfev"].get<double>() * per_impact;
      measured.steps_per_impact = point["steps"].get<double>() * per_impact;
      measured.errors = impact_errors(result.reference, impacts);
      measured.termination = point["termination"];
      result.points.push_back(measured);
    }
  }
}

std::vector<WorkPrecisionPoint> of_tool(const std::vector<WorkPrecisionPoint>& points,
                                        const std::string& tool) {
  std::vector<WorkPrecisionPoint> selected;
  for (const auto& point : points)
    if (point.tool == tool) selected.push_back(point);
  return selected;
}

nlohmann::json point_record(const WorkPrecisionPoint& point) {
  return {{"tool", point.tool},
          {"method", point.method},
          {"rtol", point.rtol},
          {"atol", point.atol},
          {"seconds_per_impact", point.seconds_per_impact},
          {"wall_seconds_per_impact", point.wall_seconds_per_impact},
          {"impacts_per_second", 1.0 / point.seconds_per_impact},
          {"max_time_error", point.errors.time},
          {"max_velocity_error", point.errors.velocity}};
}

int run_bench(const BenchOptions& options, const std::vector<std::string>& command_line) {
  const auto wall_start = std::chrono::steady_clock::now();
  const BenchPlan plan = plan_for(options.quick);
  const int repetitions = options.repetitions > 0 ? options.repetitions : options.quick ? 1 : 3;
  const std::filesystem::path directory = options.out;
  // the data file and its sidecar, committed together at the end; the
  // directory (created now, so that a bad --out is refused before the run)
  // goes again if the run fails before that
  RunFiles run_files = open_run_files(directory);

  // the references first: they set N for every case
  std::vector<CaseResult> results;
  for (const auto& bench_case : bench_cases()) {
    CaseResult result{bench_case, load_scene(bench_case.scene), 0.0, {}, {}};
    for (const auto& assignment : bench_case.assignments) apply_override(result.scene, assignment);
    if (result.scene.oscillator == "bouncing_ball") start_on_period_one_orbit(result.scene);
    result.forcing_period = result.scene.forcing_period();
    const double t_reference =
        result.scene.number("t0") + plan.reference_periods * result.forcing_period;
    result.reference = bench_reference(result.scene, t_reference, plan.max_reference_impacts);
    if (result.reference.impacts.empty())
      throw std::runtime_error("bench: case " + bench_case.name + " has no trusted reference impact");
    results.push_back(std::move(result));
  }

  // impactlab: every stepper over the ladder; the exact flow once
  std::size_t total = 0, done = 0;
  for (const auto& result : results)
    total += plan.rtols.size() * (stepper_names.size() - 1) + (has_closed_form(result.scene) ? 1 : 0);
  {
    ProgressBar progress(!options.quiet);
    for (auto& result : results) {
      for (const auto method : stepper_names) {
        if (method == "exact") {
          if (!has_closed_form(result.scene)) continue;
          result.points.push_back(measure_point(result.scene, "exact", 1e-10, 1e-12,
                                                plan.timed_periods, repetitions,
                                                result.reference));
          progress.update(static_cast<double>(++done) / static_cast<double>(total));
          continue;
        }
        for (const double rtol : plan.rtols) {
          result.points.push_back(measure_point(result.scene, std::string(method), rtol,
                                                plan.atol_ratio * rtol, plan.timed_periods,
                                                repetitions, result.reference));
          progress.update(static_cast<double>(++done) / static_cast<double>(total));
        }
      }
    }
  }

  nlohmann::json scipy_versions = nullptr;
  if (options.scipy) run_scipy(options, plan, results, directory, scipy_versions);

  // the targets, the recommended defaults and the long run
  constexpr double target_time_error = 1e-9;  // s
  nlohmann::json cases_record = nlohmann::json::array();
  nlohmann::json targets = nlohmann::json::object();
  for (const auto& result : results) {
    const auto own = of_tool(result.points, "impactlab");
    const WorkPrecisionPoint* recommended = cheapest_within(own, target_time_error);
    nlohmann::json record = {
        {"name", result.bench_case.name},
        {"scene", scene_record(result.scene)},
        {"forcing_period", result.forcing_period},
        {"reference",
         {{"method", result.reference.method},
          {"impacts_compared", result.reference.impacts.size()},
          {"impacts_computed", result.reference.impacts_computed},
          {"time_spread", result.reference.time_spread},
          {"velocity_spread", result.reference.velocity_spread}}},
        {"recommended_at_time_error_1e-9",
         recommended ? point_record(*recommended) : nlohmann::json(nullptr)},
    };
    nlohmann::json front = nlohmann::json::array();
    for (const auto& point : pareto_front(own)) front.push_back(point_record(point));
    record["impactlab_front"] = front;
    const auto scipy = of_tool(result.points, "scipy");
    if (!scipy.empty()) {
      nlohmann::json ratios = nlohmann::json::array();
      std::vector<double> values, dop853_values;
      for (const auto& ratio : speed_ratios(scipy, own)) {
        if (ratio.slow_method == "DOP853") dop853_values.push_back(ratio.ratio);
        ratios.push_back({{"scipy_method", ratio.slow_method},
                          {"scipy_rtol", ratio.slow_rtol},
                          {"scipy_time_error", ratio.slow_error},
                          {"impactlab_method", ratio.fast_method},
                          {"impactlab_rtol", ratio.fast_rtol},
                          {"impactlab_time_error", ratio.fast_error},
                          {"speed_ratio", ratio.ratio}});
        values.push_back(ratio.ratio);
      }
      record["speed_ratio_vs_scipy_at_equal_or_better_error"] = ratios;
      // the least and the median ratio, as `<prefix>_min` and `<prefix>_median`
      const auto record_spread = [&](const std::string& prefix, std::vector<double> of) {
        if (of.empty()) return;
        std::sort(of.begin(), of.end());
        record[prefix + "_min"] = of.front();
        record[prefix + "_median"] = of[of.size() / 2];
      };
      record_spread("speed_ratio_vs_scipy", values);
      record_spread("speed_ratio_vs_scipy_dop853", dop853_values);
    }
    if (result.bench_case.name == "jin2003_periodic") {
      // the Taylor stepper's goals: 3·10^5 impacts/s at an impact-time error <= 1e-9 s,
      // 2·10^5 at <= 1e-12 s (one core)
      targets["impacts_per_second_at_time_error_1e-9_jin2003"] = {
          {"goal", 3e5},
          {"best", recommended ? point_record(*recommended) : nlohmann::json(nullptr)},
          {"reached", recommended && 1.0 / recommended->seconds_per_impact >= 3e5}};
      const WorkPrecisionPoint* finest = cheapest_within(own, 1e-12);
      targets["impacts_per_second_at_time_error_1e-12_jin2003"] = {
          {"goal", 2e5},
          {"best", finest ? point_record(*finest) : nlohmann::json(nullptr)},
          {"reached", finest && 1.0 / finest->seconds_per_impact >= 2e5}};
      // at least 300 times SciPy's loop at equal or better error: over every
      // SciPy method, and the Taylor stepper's own, against DOP853 alone
      const auto ratio_target = [&](const std::string& target, const std::string& of) {
        if (!record.contains(of + "_min")) return;
        targets[target] = {{"goal", 300.0},
                           {"min", record[of + "_min"]},
                           {"median", record[of + "_median"]},
                           {"reached", record[of + "_min"].get<double>() >= 300.0}};
      };
      ratio_target("speed_ratio_vs_scipy_pendulum", "speed_ratio_vs_scipy");
      ratio_target("speed_ratio_vs_scipy_dop853_pendulum", "speed_ratio_vs_scipy_dop853");
    }
    cases_record.push_back(record);
  }

  // 10^6 impacts of the periodic pendulum with its recommended stepper: the
  // time per impact in the first and the last tenth (no slowdown)
  nlohmann::json long_run = nullptr;
  if (plan.long_run_periods > 0.0) {
    const auto own = of_tool(results.front().points, "impactlab");
    if (const WorkPrecisionPoint* chosen = cheapest_within(own, target_time_error)) {
      const WorkPrecisionPoint point =
          measure_point(results.front().scene, chosen->method, chosen->rtol, chosen->atol,
                        plan.long_run_periods, 1, results.front().reference);
      long_run = {{"case", results.front().bench_case.name},
                  {"method", point.method},
                  {"rtol", point.rtol},
                  {"atol", point.atol},
                  {"forcing_periods", plan.long_run_periods},
                  {"impacts", point.impacts},
                  {"seconds_per_impact", point.seconds_per_impact},
          {"wall_seconds_per_impact", point.wall_seconds_per_impact},
                  {"first_tenth_seconds_per_impact", point.first_tenth_seconds_per_impact},
                  {"last_tenth_seconds_per_impact", point.last_tenth_seconds_per_impact},
                  {"last_over_first",
                   point.last_tenth_seconds_per_impact / point.first_tenth_seconds_per_impact},
                  {"termination", point.termination}};
    }
  }

  // the data file
  AtomicFile& csv = run_files.add("work_precision.csv");
  csv.stream() << "case,oscillator,tool,method,rtol,atol,impacts,seconds_per_impact,"
                  "impacts_per_second,wall_seconds_per_impact,rhs_per_impact,steps_per_impact,compared_impacts,"
                  "reference_impacts,max_time_error,max_velocity_error,"
                  "first_tenth_seconds_per_impact,last_tenth_seconds_per_impact,termination\n";
  std::size_t rows = 0;
  for (const auto& result : results) {
    for (const auto& point : result.points) {
      csv.stream() << fmt::format(
          "{},{},{},{},{:.3g},{:.3g},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
          result.bench_case.name, result.scene.oscillator, point.tool, point.method, point.rtol,
          point.atol, point.impacts, number_text(point.seconds_per_impact),
          number_text(1.0 / point.seconds_per_impact),
          number_text(point.wall_seconds_per_impact), number_text(point.rhs_per_impact),
          number_text(point.steps_per_impact), point.errors.compared, point.errors.reference,
          number_text(point.errors.time), number_text(point.errors.velocity),
          number_text(point.first_tenth_seconds_per_impact),
          number_text(point.last_tenth_seconds_per_impact), point.termination);
      ++rows;
    }
  }

  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"quick", options.quick},
      {"repetitions", repetitions},
      {"timed_forcing_periods", plan.timed_periods},
      {"reference_forcing_periods", plan.reference_periods},
      {"atol_over_rtol", plan.atol_ratio},
      {"scipy", options.scipy ? nlohmann::json{{"script", "scripts/scipy_event_loop.py"},
                                               {"python", options.python},
                                               {"versions", scipy_versions}}
                              : nlohmann::json(nullptr)},
      {"cases", cases_record},
      {"targets", targets},
      {"long_run", long_run},
      {"wall_time_s", wall_time},
      {"counts", {{"rows", rows}, {"cases", results.size()}}},
      {"columns",
       {{"case", "bench case (scene and --set below)"},
        {"tool", "impactlab | scipy"},
        {"method", "stepper (impactlab) or solve_ivp method (scipy)"},
        {"rtol", "relative tolerance"},
        {"atol", "absolute tolerance (state units)"},
        {"impacts", "impacts of the timed run"},
        {"seconds_per_impact",
         "CPU s of the running thread per impact (one core; on a shared machine this, unlike "
         "wall time, does not grow with the other processes' load); impactlab: median of the "
         "repetitions over the timed forcing periods; scipy: one run over the reference "
         "forcing periods (time.thread_time)"},
        {"impacts_per_second", "1 / seconds_per_impact"},
        {"wall_seconds_per_impact", "wall s per impact, same runs (median for impactlab)"},
        {"rhs_per_impact", "right-hand-side evaluations per impact"},
        {"steps_per_impact", "accepted steps per impact"},
        {"compared_impacts", "impacts compared with the reference"},
        {"reference_impacts", "impacts in the reference (compared < reference: the run's "
                              "impact sequence ended early)"},
        {"max_time_error", "largest |t - t_ref| over the compared impacts (s; linear_impact: "
                           "its time unit)"},
        {"max_velocity_error", "largest |qdot_before - ref| (rad/s, m/s or length/time)"},
        {"first_tenth_seconds_per_impact", "CPU s per impact over the first tenth of the "
                                           "simulated time (first repetition; impactlab only)"},
        {"last_tenth_seconds_per_impact", "the same over 0.89 .. 0.99 of the simulated time"},
        {"termination", "of the timed run"}}},
      {"files", {"work_precision.csv", "work_precision.json"}},
  };
  write_json(run_files.add("work_precision.json"), meta);
  run_files.commit();

  if (options.plots) {
    const std::string script = program_file("scripts/plot_bench.py").string();
    const std::vector<std::string> command = {options.python, script, directory.string()};
    if (run_program(command) != 0)
      throw std::runtime_error("plotting failed: " + describe_program(command));
  }

  if (!options.quiet) {
    for (const auto& record : cases_record) {
      std::cout << fmt::format("{}: reference {} ({} impacts, spread {:.2g} s)",
                               record["name"].get<std::string>(),
                               record["reference"]["method"].get<std::string>(),
                               record["reference"]["impacts_compared"].get<std::size_t>(),
                               record["reference"]["time_spread"].get<double>());
      if (record.contains("speed_ratio_vs_scipy_min"))
        std::cout << fmt::format(", speed ratio vs SciPy at equal error: min {:.0f}, median {:.0f}",
                                 record["speed_ratio_vs_scipy_min"].get<double>(),
                                 record["speed_ratio_vs_scipy_median"].get<double>());
      if (record.contains("speed_ratio_vs_scipy_dop853_min"))
        std::cout << fmt::format(" (DOP853: min {:.0f})",
                                 record["speed_ratio_vs_scipy_dop853_min"].get<double>());
      const auto& recommended = record["recommended_at_time_error_1e-9"];
      if (!recommended.is_null())
        std::cout << fmt::format(", cheapest at error <= 1e-9: {} rtol {:g} ({:.0f} impacts/s)",
                                 recommended["method"].get<std::string>(),
                                 recommended["rtol"].get<double>(),
                                 recommended["impacts_per_second"].get<double>());
      std::cout << '\n';
    }
    std::cout << "wrote " << (directory / "work_precision.json").string() << '\n';
  }
  return exit_done;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "bench",
      "work-precision data: cost against impact-time error per stepper and tolerance, "
      "beside a SciPy solve_ivp event loop");
  auto options = std::make_shared<BenchOptions>();
  TableOptions table(*command, "bench");
  table.add("out", options->out);
  table.add("quick", options->quick);
  table.add_negation("no_scipy", options->scipy);
  table.add_negation("no_plots", options->plots);
  table.add("repetitions", options->repetitions);
  table.add("python", options->python);
  table.add("quiet", options->quiet);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_bench(*options, command_line);
          },
          "bench"};
}

}  // namespace impactlab::cli
