// `impactlab poincare`: a scene's Poincaré section after a transient;
// writes poincare.csv (k,t,q,qdot; the impact map adds wall,phase) and
// meta.json, atomically (meta.json last); --lyapunov-spectrum adds
// lyapunov.csv (the running estimate of the N exponents); --plot adds
// poincare.png (and lyapunov.png).
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/section_record.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "table_options.hpp"
#include "section_options.hpp"
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

std::string number(double value) { return fmt::format("{}", value); }

// poincare.csv, one row per point as the run finds it (memory does not grow
// with --points)
class PoincareCsvWriter final : public SectionPointSink {
 public:
  PoincareCsvWriter(std::ofstream& out, bool impact_map, bool user_section)
      : out_(out), impact_map_(impact_map), user_section_(user_section) {
    out_ << (impact_map ? "k,t,q,qdot,wall,phase\n"
                        : user_section ? "k,t,q,qdot,phase\n" : "k,t,q,qdot\n");
  }
  void begin(double omega) override { omega_ = omega; }
  void write(const SectionPoint& p) override {
    out_ << index_++ << ',' << number(p.t) << ',' << number(p.q) << ',' << number(p.qdot);
    if (impact_map_) out_ << ',' << p.wall;
    if (impact_map_ || user_section_)
      out_ << ',' << number(std::fmod(omega_ * p.t, 2.0 * std::numbers::pi));
    out_ << '\n';
  }

 private:
  std::ofstream& out_;
  bool impact_map_, user_section_;
  double omega_ = 0.0;  // rad per time unit, from begin()
  std::uint64_t index_ = 0;
};

// lyapunov.csv: the running estimate of each exponent, one row per averaged
// forcing period as the tangent run reaches it
class LyapunovCsvWriter final : public LyapunovSpectrumSink {
 public:
  explicit LyapunovCsvWriter(std::ofstream& out) : out_(out) {}
  void begin(std::size_t exponents) override {
    out_ << "# running estimate of each Lyapunov exponent over the forcing periods averaged so "
            "far; t: the end of the period (scene time unit), lambda1..lambda"
         << exponents << ": 1/(scene time unit), -inf where the contact collapsed the direction\n"
         << "t";
    for (std::size_t i = 1; i <= exponents; ++i) out_ << ",lambda" << i;
    out_ << '\n';
  }
  void write(double t, const std::vector<double>& running) override {
    out_ << number(t);
    for (double value : running) out_ << ',' << number(value);
    out_ << '\n';
  }

 private:
  std::ofstream& out_;
};

// a finite number, or null (−∞ and NaN: the entry's note says which)
nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// meta.json's spectrum: the exponents with null for −∞ (JSON has no
// infinities; the note says so), their spread, and how they were made
void add_spectrum(nlohmann::json& meta, const SectionResult& result, int alignment_periods) {
  nlohmann::json exponents = nlohmann::json::array(), errors = nlohmann::json::array();
  bool collapsed = false;
  for (std::size_t i = 0; i < result.lyapunov_spectrum.size(); ++i) {
    exponents.push_back(finite_or_null(result.lyapunov_spectrum[i]));
    errors.push_back(finite_or_null(result.lyapunov_spectrum_error[i]));
    collapsed = collapsed || result.lyapunov_spectrum[i] == -INFINITY;
  }
  bool computed = !result.lyapunov_spectrum.empty();
  for (double value : result.lyapunov_spectrum) computed = computed && !std::isnan(value);
  std::string note = result.lyapunov_spectrum_note;
  if (collapsed)
    note = "null: -inf, a direction the contact collapsed (an accumulation of impacts or a "
           "sticking phase merged nearby states)";
  meta["lyapunov_spectrum"] = computed ? exponents : nlohmann::json(nullptr);
  meta["lyapunov_spectrum_error"] = computed ? errors : nlohmann::json(nullptr);
  meta["lyapunov_spectrum_info"] = {
      {"unit", "1/(scene time unit)"},
      {"method", "QR re-orthonormalisation of N tangent vectors once per forcing period "
                 "(variational equations in flight, saltation matrices at events)"},
      {"error", "half the range of each running estimate over the last quarter of the "
                "averaging periods"},
      {"alignment_periods", alignment_periods},
      {"note", note}};
}

int run_poincare(const SectionOptions& options, bool lyapunov, bool spectrum,
                 const std::vector<std::string>& command_line) {
  const Scene scene = options.scene.load();
  SectionRequest request = options.request();
  request.lyapunov = lyapunov;
  request.lyapunov_spectrum = spectrum;
  const auto directory = options.scene.output_directory();
  // poincare.csv and meta.json, committed together (meta.json last)
  RunFiles files = open_run_files(directory);

  const bool impact_map = request.section.kind == SectionKind::impact;
  const bool user_section = request.section.kind != SectionKind::impact &&
                            request.section.kind != SectionKind::strobe;
  PoincareCsvWriter rows(files.add("poincare.csv").stream(), impact_map, user_section);
  request.point_sink = &rows;
  std::optional<LyapunovCsvWriter> spectrum_rows;
  if (spectrum) {
    spectrum_rows.emplace(files.add("lyapunov.csv").stream());
    request.lyapunov_spectrum_sink = &*spectrum_rows;
  }

  const auto start = std::chrono::steady_clock::now();
  const SectionResult result = poincare(scene, request);
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const SceneSchema& schema = scene_schema(scene);
  const std::string q_name(schema.main_coordinate);

  nlohmann::json meta = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"scene", scene_record(scene)},
      {"section", section_request_record(options.section, request)},
      {"termination", to_string(result.termination)},
      {"forcing_period", result.forcing_period},
      {"record_start", result.record_start},
      {"transient", {{"periods", result.transient_periods},
                     {"end", to_string(result.transient_end)}}},
      {"counts",
       {{"points", result.point_count},
        {"periods_recorded", result.periods_recorded},
        {"impacts_recorded", result.impacts},
        {"contact_phases_recorded", result.contact_phases},
        {"steps", result.steps},
        {"rhs_evaluations", result.rhs_evaluations}}},
      {"wall_time_s", wall_time},
      {"columns",
       {{"k", "index of the section point"},
        {"t", "time of the point (scene time unit)"},
        {"q", q_name},
        {"qdot", "d" + q_name + "/dt" + (impact_map ? " just before the impact" : "")},
        {"wall", "wall hit (+1 / -1), impact map only"},
        {"phase", "forcing phase omega t mod 2 pi (rad), impact map and user-given sections"}}},
      {"files", spectrum ? nlohmann::json{"poincare.csv", "lyapunov.csv", "meta.json"}
                         : nlohmann::json{"poincare.csv", "meta.json"}},
  };
  if (lyapunov) {
    // a number; null where there is none (NaN: the note says why)
    meta["lyapunov"] = {{"largest_exponent_per_time", std::isfinite(result.lyapunov)
                                                          ? nlohmann::json(result.lyapunov)
                                                          : nlohmann::json(nullptr)},
                        {"note", result.lyapunov_note}};
  }
  if (spectrum) add_spectrum(meta, result, request.lyapunov_alignment_periods);
  write_json(files.add("meta.json"), meta);
  files.commit();

  if (options.plot) {
    plot_with_python("poincare", directory / "poincare.csv", directory / "poincare.png",
                     {q_name});
    if (spectrum)
      plot_with_python("lyapunov", directory / "lyapunov.csv", directory / "lyapunov.png", {});
  }
  if (!options.scene.quiet)
    std::cout << fmt::format(
        "{}: {} section points ({}) after a transient of {:g} forcing periods ({}), {:.3f} s "
        "wall\nwrote {}\n",
        scene.name, result.point_count, to_string(request.section), result.transient_periods,
        to_string(result.transient_end), wall_time, (directory / "poincare.csv").string());
  // said even when quiet: the points may be a transient's
  if (result.transient_end == TransientEnd::not_settled)
    std::cerr << fmt::format(
        "impactlab: warning: the transient did not settle within max_transient = {:g} forcing "
        "periods: the points may still be on their way to the attractor\n",
        request.max_transient_periods);
  if (result.termination != SectionTermination::completed) {
    std::cerr << fmt::format("impactlab: run stopped early ({}); {} points recorded\n",
                             to_string(result.termination), result.point_count);
    return exit_stopped_early;
  }
  return exit_done;
}

}  // namespace

Command add_poincare_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "poincare", "a Poincare section after a transient; write poincare.csv and meta.json");
  auto options = std::make_shared<SectionOptions>();
  auto lyapunov = std::make_shared<bool>(false);
  auto spectrum = std::make_shared<bool>(false);
  TableOptions table(*command, "poincare");
  options->add_to(table);
  table.add("lyapunov", *lyapunov);
  table.add("lyapunov_spectrum", *spectrum);
  return {command,
          [options, lyapunov, spectrum](const std::vector<std::string>& command_line) {
            return run_poincare(*options, *lyapunov, *spectrum, command_line);
          },
          "poincare"};
}

}  // namespace impactlab::cli
