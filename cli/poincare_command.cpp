// `impactlab poincare`: a scene's Poincaré section after a transient;
// writes poincare.csv (k,t,q,qdot; the impact map adds wall,phase) and
// meta.json, atomically (meta.json last); --plot adds poincare.png.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <numbers>

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

int run_poincare(const SectionOptions& options, bool lyapunov,
                 const std::vector<std::string>& command_line) {
  const Scene scene = options.scene.load();
  SectionRequest request = options.request();
  request.lyapunov = lyapunov;
  const auto directory = options.scene.output_directory();
  // poincare.csv and meta.json, committed together (meta.json last)
  RunFiles files = open_run_files(directory);

  const bool impact_map = request.section.kind == SectionKind::impact;
  const bool user_section = request.section.kind != SectionKind::impact &&
                            request.section.kind != SectionKind::strobe;
  PoincareCsvWriter rows(files.add("poincare.csv").stream(), impact_map, user_section);
  request.point_sink = &rows;

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
      {"files", {"poincare.csv", "meta.json"}},
  };
  if (lyapunov) {
    // a number; null where there is none (NaN: the note says why)
    meta["lyapunov"] = {{"largest_exponent_per_time", std::isfinite(result.lyapunov)
                                                          ? nlohmann::json(result.lyapunov)
                                                          : nlohmann::json(nullptr)},
                        {"note", result.lyapunov_note}};
  }
  write_json(files.add("meta.json"), meta);
  files.commit();

  if (options.plot)
    plot_with_python("poincare", directory / "poincare.csv", directory / "poincare.png",
                     {q_name});
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
  TableOptions table(*command, "poincare");
  options->add_to(table);
  table.add("lyapunov", *lyapunov);
  return {command,
          [options, lyapunov](const std::vector<std::string>& command_line) {
            return run_poincare(*options, *lyapunov, command_line);
          },
          "poincare"};
}

}  // namespace impactlab::cli
