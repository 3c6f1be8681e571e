#include <impactlab/api/jin2003_report.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include <fmt/format.h>

#include <impactlab/io/output.hpp>
#include <impactlab/oscillators/pendulum_walls/sliding_impact.hpp>

namespace impactlab {

namespace {

std::string model_label(std::string_view model) {
  if (model == "paper") return "Model P";
  if (model == "newton") return "Model N";
  if (model.starts_with("rigid")) {
    std::string settings(model.substr(std::min(model.size(), std::size_t{6})));
    std::replace(settings.begin(), settings.end(), ':', ',');
    return settings.empty() ? "rigid body" : fmt::format("rigid body ({})", settings);
  }
  return std::string(model);
}

std::string format_ranges(const std::vector<ParameterRange>& ranges) {
  if (ranges.empty()) return "none";
  std::string text;
  for (const auto& r : ranges) {
    if (!text.empty()) text += ", ";
    text += r.from == r.to ? fmt::format("{:.3f}", r.from)
                           : fmt::format("{:.3f}–{:.3f}", r.from, r.to);
  }
  return text;
}

nlohmann::json ranges_json(const std::vector<ParameterRange>& ranges) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& r : ranges) list.push_back({r.from, r.to});
  return list;
}

// The distance between two sets of ranges: the largest endpoint difference
// when they pair up one to one, infinity otherwise.
double endpoint_distance(const std::vector<ParameterRange>& a, const std::vector<ParameterRange>& b) {
  if (a.size() != b.size() || a.empty()) return std::numeric_limits<double>::infinity();
  double distance = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    distance = std::max({distance, std::fabs(a[i].from - b[i].from), std::fabs(a[i].to - b[i].to)});
  return distance;
}

// the largest steady-state |v_y0| of a model within [from, to] of a panel
double largest_tangential_speed(const ResidualPanel& panel, std::string_view model, double from,
                                double to) {
  double largest = 0.0;
  for (const auto& row : panel.rows)
    if (row.model == model && row.parameter >= from && row.parameter <= to)
      largest = std::max(largest, std::fabs(row.tangential_velocity));
  return largest;
}

// The smallest tolerance δ (m/s) at which every grid value of `range` counts
// as "sliding possible" for `model`: the largest, over those values, of the
// smallest |r| of their steady-state impacts. Infinity where some value has
// no residual (no steady state, or V0 ω < g).
double tolerance_to_cover(const ResidualPanel& panel, std::string_view model,
                          const ParameterRange& range) {
  double needed = 0.0;
  bool any = false;
  for (const auto& summary : panel.summaries) {
    if (summary.model != model || summary.parameter < range.from - 1e-12 ||
        summary.parameter > range.to + 1e-12)
      continue;
    any = true;
    if (std::isnan(summary.min_abs_residual)) return std::numeric_limits<double>::infinity();
    needed = std::max(needed, summary.min_abs_residual);
  }
  return any ? needed : std::numeric_limits<double>::quiet_NaN();
}

double largest_abs_residual(const ResidualPanel& panel, std::string_view model) {
  double largest = 0.0;
  for (const auto& row : panel.rows)
    if (row.model == model && !std::isnan(row.sliding_residual))
      largest = std::max(largest, std::fabs(row.sliding_residual));
  return largest;
}

void write_residual_csv(const ResidualPanel& panel, AtomicFile& file) {
  auto& out = file.stream();
  out << panel.parameter
      << ",model,k,t,wall,normal_speed,tangential_velocity,sliding_residual,"
         "instantaneous_residual,sliding_impact\n";
  for (const auto& r : panel.rows)
    out << csv_field(r.parameter) << ',' << r.model << ',' << r.k << ',' << csv_field(r.t) << ','
        << r.wall << ',' << csv_field(r.normal_speed) << ',' << csv_field(r.tangential_velocity)
        << ',' << csv_field(r.sliding_residual) << ',' << csv_field(r.instantaneous_residual)
        << ',' << (r.sliding_impact ? 1 : 0) << '\n';
}

void write_values_csv(const ResidualPanel& panel, AtomicFile& file) {
  auto& out = file.stream();
  out << panel.parameter << ",model,impacts,recorded,min_abs_sliding_residual,sliding_impacts,"
                            "termination\n";
  for (const auto& s : panel.summaries)
    out << csv_field(s.parameter) << ',' << s.model << ',' << s.impacts << ',' << s.recorded << ','
        << csv_field(s.min_abs_residual) << ',' << s.sliding_impacts << ','
        << to_string(s.termination)
        << '\n';
}

void write_history_csv(const std::vector<HistorySample>& samples, AtomicFile& file) {
  auto& out = file.stream();
  out << "model,t,x,mode\n";
  for (const auto& s : samples)
    out << s.model << ',' << csv_field(s.t) << ',' << csv_field(s.x) << ',' << s.mode << '\n';
}

nlohmann::json residual_columns(const ResidualPanel& panel) {
  return {{panel.parameter, panel.unit},
          {"model", "impact model: paper (Model P), newton (Model N), rigid"},
          {"k", "impact number after the 200-impact transient, from 0"},
          {"t", "s"},
          {"wall", "+1 right, -1 left"},
          {"normal_speed", "m/s, v_n = l cos(theta0) |theta_dot| before the impact"},
          {"tangential_velocity", "m/s, v_y0 along the wall, y down, before the impact"},
          {"sliding_residual",
           "m/s, sqrt(V0^2 - (g/omega)^2) + e_y v_y0, the paper's Fig. 4 'v_c0 - v_y0' "
           "(Eqs. 21-22); empty where V0 omega < g"},
          {"instantaneous_residual", "m/s, (1 + e_n) tan(theta0) v_n + (1 + e_y) v_y0 (Eq. 26)"},
          {"sliding_impact", "1 if the impact started a sliding phase"}};
}

std::string markdown_report(const Jin2003Results& results, const Jin2003Settings& settings,
                            const Scene& scene, const nlohmann::json& provenance) {
  const PaperRanges paper;
  const double g = scene.number("g"), e_t = scene.number("e_t");
  std::string md;
  auto line = [&md](const std::string& text = "") {
    md += text;
    md += '\n';
  };

  line("# Jin, Hu & Bishop (2003), Fig. 4, reproduced by impactlab");
  line();
  line(fmt::format("Made by `{}` (impactlab {}, {}), {:.1f} s wall on {} thread(s). "
                   "Every number below is computed from the CSV files beside this report "
                   "(`report.json` has them machine-readable; `tests/jin2003_reproduction_test` "
                   "re-derives them).",
                   provenance.value("command_line", std::string("impactlab reproduce jin2003")),
                   provenance.value("impactlab_version", std::string("?")),
                   provenance.value("created_utc", std::string("?")), results.wall_time,
                   settings.threads));
  line();
  line(fmt::format(
      "Scene `jin2003`: m = {} kg, l = {} m, b = {} m, d = {} N m s/rad, μ = {}, e_n = {}, "
      "e_y = {}, θ(0) = {} rad, θ̇(0) = {} rad/s; integrator {} at rtol {:g}, atol {:g}. "
      "Steady state as in the paper: the first {} impacts are discarded, the next {} kept, "
      "from runs of {} forcing periods.",
      scene.number("m"), scene.number("l"), scene.number("b"), scene.number("d"),
      scene.number("mu"), scene.number("e_n"), e_t, scene.number("initial.theta"),
      scene.number("initial.theta_dot"), scene.text("integrator.method"),
      scene.number("integrator.rtol"), scene.number("integrator.atol"),
      settings.transient_impacts, settings.recorded_impacts, settings.periods));
  line();
  line("## What is plotted");
  line();
  line("Fig. 4(a, b) plot the sliding-impact residual at each steady-state impact, "
       "r = √(V0² − (g/ω)²) + e_y v_y0 (m/s): the tangential velocity a slip ends with "
       "when it ends where the normal force vanishes (Eqs. 20–21), minus the velocity the "
       "paper's tangential restitution asks for, −e_y v_y0. r = 0 is the paper's Eq. 22, its "
       "condition for a sliding impact; the paper calls the plotted quantity \"v_c0 − v_y0\". "
       "Where V0 ω < g the effective gravity never vanishes, no slip can end, and r is "
       "undefined (blank in the CSV). `docs/model-card.md` gives the reading of each garbled "
       "symbol. Fig. 4(c, d) plot the bob's horizontal displacement x = l sin θ at "
       "V0 = 4.163 m/s, ω = 7 rad/s.");
  line();
  line("## Ranges where sliding is possible");
  line();
  line("The paper reads its ranges off plots where r is \"close to zero\" and states no "
       "tolerance. The toolkit gives the ranges of grid values where some steady-state impact "
       "has |r| ≤ δ, for three δ:");
  line();
  std::string header = "| quantity | model |";
  std::string rule = "|---|---|";
  for (double tolerance : report_tolerances()) {
    header += fmt::format(" δ = {} m/s |", tolerance);
    rule += "---|";
  }
  line(header + " paper |");
  line(rule + "---|");
  for (const ResidualPanel* panel : {&results.fig4a, &results.fig4b}) {
    const bool over_omega = panel->parameter == "omega";
    const std::string quantity =
        fmt::format("{} ({}) at {} = {} {}", over_omega ? "ω" : "V0", panel->unit,
                    over_omega ? "V0" : "ω", panel->fixed_value, over_omega ? "m/s" : "rad/s");
    for (const auto& model : settings.models) {
      std::string row = fmt::format("| {} | {} |", quantity, model_label(model));
      for (double tolerance : report_tolerances())
        row += fmt::format(" {} |", format_ranges(sliding_ranges(*panel, model, tolerance)));
      line(row + fmt::format(" {} |", format_ranges(over_omega ? paper.omega : paper.V0)));
    }
  }
  line();
  line(fmt::format("Grids: ω from {} to {} rad/s in {} values; V0 from {} to {} m/s in {} values.",
                   settings.omega_from, settings.omega_to, settings.omega_points,
                   settings.V0_from, settings.V0_to, settings.V0_points));
  line();

  // how close: the tolerance that comes closest to the paper's ω range
  line("## How close the reproduction came");
  line();
  const std::string& first_model = settings.models.front();
  double best_tolerance = NAN, best_distance = std::numeric_limits<double>::infinity();
  for (double tolerance : report_tolerances()) {
    const double distance =
        endpoint_distance(sliding_ranges(results.fig4a, first_model, tolerance), paper.omega);
    if (distance < best_distance) {
      best_distance = distance;
      best_tolerance = tolerance;
    }
  }
  const double omega_threshold = g / settings.V0_of_fig4a;
  const double V0_threshold = g / settings.omega_of_fig4b;
  if (std::isfinite(best_distance)) {
    const auto best = sliding_ranges(results.fig4a, first_model, best_tolerance);
    line(fmt::format(
        "* **ω range at V0 = {} m/s.** The paper gives {}. The toolkit's {} range with "
        "δ = {} m/s is {}: the ends differ by {:.3f} and {:.3f} rad/s, the largest difference "
        "{:.3f} rad/s ({:.1f} % of the paper's range). Sliding cannot start below "
        "ω = g / V0 = {:.4f} rad/s, where V0 ω = g; the paper's lower end, 6.6 rad/s, lies "
        "{:.3f} rad/s above it.",
        settings.V0_of_fig4a, format_ranges(paper.omega), model_label(first_model),
        best_tolerance, format_ranges(best), best.front().from - paper.omega.front().from,
        best.back().to - paper.omega.back().to, best_distance,
        100.0 * best_distance / (paper.omega.back().to - paper.omega.front().from),
        omega_threshold, paper.omega.front().from - omega_threshold));
  } else {
    line(fmt::format("* **ω range at V0 = {} m/s.** The paper gives {}; no tolerance gives "
                     "the toolkit one range to compare end to end.",
                     settings.V0_of_fig4a, format_ranges(paper.omega)));
  }
  const auto exact_V0 = sliding_ranges(results.fig4b, first_model, report_tolerances().front());
  const auto loose_V0 = sliding_ranges(results.fig4b, first_model, report_tolerances().back());
  line(fmt::format(
      "* **First V0 range at ω = {} rad/s.** The paper gives 1.5–1.6 m/s. The toolkit's {} "
      "finds {} at δ = {} m/s and {} at δ = {} m/s. Sliding cannot start below "
      "V0 = g / ω = {:.4f} m/s; the paper's range lies {:.3f}–{:.3f} m/s above that "
      "threshold, where the toolkit's residual has already grown.",
      settings.omega_of_fig4b, model_label(first_model), format_ranges(exact_V0),
      report_tolerances().front(), format_ranges(loose_V0), report_tolerances().back(),
      V0_threshold, paper.V0.front().from - V0_threshold, paper.V0.front().to - V0_threshold));
  line(fmt::format(
      "* **The tolerance the paper's ranges imply.** For every grid value inside a paper "
      "range to count as sliding possible, the toolkit's {} needs δ = {:.3f} m/s for the "
      "ω range {}, δ = {:.3f} m/s for the V0 range {}, and δ = {:.3f} m/s for the V0 range "
      "{}, against a largest steady-state |r| of {:.3f} m/s over the whole of Fig. 4(b).",
      model_label(first_model),
      tolerance_to_cover(results.fig4a, first_model, paper.omega.front()),
      format_ranges(paper.omega),
      tolerance_to_cover(results.fig4b, first_model, paper.V0.front()),
      format_ranges({paper.V0.front()}),
      tolerance_to_cover(results.fig4b, first_model, paper.V0.back()),
      format_ranges({paper.V0.back()}), largest_abs_residual(results.fig4b, first_model)));
  const ParameterRange second = paper.V0.back();
  const double needed = slip_end_velocity(second.from, settings.omega_of_fig4b, g) / std::fabs(e_t);
  const double found =
      largest_tangential_speed(results.fig4b, first_model, second.from, second.to);
  const double lowest_residual =
      slip_end_velocity(second.from, settings.omega_of_fig4b, g) - std::fabs(e_t) * found;
  line(fmt::format(
      "* **Second V0 range, {}–{} m/s: not reproduced, and not reproducible under Eq. 22 "
      "with this scene's velocities.** There r = 0 needs |v_y0| = √(V0² − (g/ω)²) / |e_y| "
      "≥ {:.1f} m/s, while the largest steady-state |v_y0| the toolkit finds there is "
      "{:.3f} m/s (the pivot's own speed is at most V0, and the bob adds "
      "l sin θ0 |θ̇| to it); so |r| ≥ {:.2f} m/s over the whole range. A reading of the "
      "garbled residual that scales r (for example v_y0 − v_c0/|e_y|) changes the plot's "
      "scale but not where r vanishes, so no reading of the symbols recovers this range.",
      second.from, second.to, needed, found, lowest_residual));
  line(fmt::format(
      "* **Tolerance.** Of the three δ, {} m/s comes closest to the paper's ω range. The "
      "tighter δ is, the closer the ranges shrink towards the threshold V0 ω = g, because "
      "|r| ≥ √(V0² − (g/ω)²) − |e_y| |v_y0| grows with the distance from it and |v_y0| stays "
      "of the order of V0.",
      best_tolerance));
  line();

  line("## Fig. 4(c, d): the slips on the walls");
  line();
  line(fmt::format("Window of Fig. 4(c): t = {:.3f} … {:.3f} s ({} forcing periods after the "
                   "later transient); zoom of Fig. 4(d): t = {:.3f} … {:.3f} s. The walls are at "
                   "x = ±{} m.",
                   results.history_from, results.history_to, settings.history_periods,
                   results.zoom_from, results.zoom_to, results.wall_position));
  line();
  line("| model | impacts | contact phases | of which sliding impacts | time on the walls | "
       "mean slip duration |");
  line("|---|---|---|---|---|---|");
  for (const auto& s : results.slips)
    line(fmt::format("| {} | {} | {} | {} | {:.3f} s ({:.1f} %) | {:.4f} s |",
                     model_label(s.model), s.impacts, s.contact_phases, s.sliding_impacts,
                     s.time_on_walls, 100.0 * s.time_on_walls / s.window, s.mean_slip_duration));
  line();
  line("The paper's Fig. 4(d) shows unidirectional slips of the ball along the walls: flat "
       "stretches of x = ±b. Under Model P each sliding impact holds the bob on the wall until "
       "the effective gravity g − V0 ω cos ωt returns to zero (Eq. 20), then gives back the "
       "normal velocity e_n v_x0. Under Model N an impact is instantaneous whatever its "
       "tangential velocity: the bob comes to rest on a wall only when a chatter of impacts "
       "accumulates while g − V0 ω cos ωt < 0, and then leaves with zero velocity at the same "
       "release condition; the chatter dissipates the energy Model P gives back. The two "
       "motions part at the first sliding impact (the table counts both in the same window). "
       "The rigid-body model's ball on a free bearing (docs/rigidbody.md) keeps Model N's "
       "instantaneous impacts; friction impulses there change the ball's spin, so its "
       "tangential restitution comes from the mechanics instead of from e_y.");
  line();
  line("## Files");
  line();
  line("`fig4a.csv`, `fig4b.csv` (one row per steady-state impact), `fig4a_values.csv`, "
       "`fig4b_values.csv` (one row per parameter value), `fig4c.csv`, `fig4d.csv` "
       "(x against t), each with a `.json` sidecar of units and provenance, the PNGs drawn by "
       "`plot_jin2003.py`, and `jin2003.ipynb`, which draws the same figures from the CSVs.");
  return md;
}

}  // namespace

void write_jin2003_outputs(const Jin2003Results& results, const Jin2003Settings& settings,
                           const Scene& scene, const nlohmann::json& provenance,
                           RunFiles& run_files) {
  const PaperRanges paper;

  // derived ranges, for report.json and the sidecars
  nlohmann::json derived;
  for (const ResidualPanel* panel : {&results.fig4a, &results.fig4b}) {
    nlohmann::json by_model;
    for (const auto& model : settings.models) {
      nlohmann::json by_tolerance;
      for (double tolerance : report_tolerances())
        by_tolerance[fmt::format("{}", tolerance)] =
            ranges_json(sliding_ranges(*panel, model, tolerance));
      by_model[model] = by_tolerance;
    }
    derived[panel == &results.fig4a ? "fig4a" : "fig4b"] = {
        {"parameter", panel->parameter},
        {"unit", panel->unit},
        {"paper", ranges_json(panel == &results.fig4a ? paper.omega : paper.V0)},
        {"toolkit", by_model}};
  }
  nlohmann::json slips = nlohmann::json::array();
  for (const auto& s : results.slips)
    slips.push_back({{"model", s.model},
                     {"impacts", s.impacts},
                     {"contact_phases", s.contact_phases},
                     {"sliding_impacts", s.sliding_impacts},
                     {"time_on_walls_s", s.time_on_walls},
                     {"window_s", s.window},
                     {"mean_slip_duration_s", s.mean_slip_duration}});

  auto sidecar = [&](const std::string& figure, nlohmann::json columns, nlohmann::json extra) {
    nlohmann::json meta = provenance;
    meta["figure"] = figure;
    meta["columns"] = std::move(columns);
    meta["settings"] = {{"models", settings.models},
                        {"transient_impacts", settings.transient_impacts},
                        {"recorded_impacts", settings.recorded_impacts},
                        {"periods", settings.periods}};
    meta.update(extra);
    return meta;
  };
  auto grid_json = [](const ResidualPanel& panel) {
    return nlohmann::json{{"parameter", panel.parameter},
                          {"unit", panel.unit},
                          {"from", panel.grid.front()},
                          {"to", panel.grid.back()},
                          {"points", panel.grid.size()},
                          {"fixed", {{panel.fixed, panel.fixed_value}}}};
  };

  auto open = [&](const std::string& name) -> AtomicFile& { return run_files.add(name); };

  for (const ResidualPanel* panel : {&results.fig4a, &results.fig4b}) {
    const std::string figure = panel == &results.fig4a ? "fig4a" : "fig4b";
    write_residual_csv(*panel, open(figure + ".csv"));
    write_values_csv(*panel, open(figure + "_values.csv"));
    write_json(open(figure + ".json"),
               sidecar(figure, residual_columns(*panel),
                       {{"grid", grid_json(*panel)},
                        {"values_file", figure + "_values.csv"},
                        {"values_columns",
                         {{"impacts", "impacts in the whole run"},
                          {"recorded", "steady-state impacts kept"},
                          {"min_abs_sliding_residual", "m/s, empty if none kept"},
                          {"sliding_impacts", "kept impacts that started a sliding phase"},
                          {"termination", "completed | stopped_by_model | no_progress"}}},
                        {"ranges", derived[figure]}}));
  }
  const nlohmann::json history_columns = {{"model", "impact model"},
                                          {"t", "s"},
                                          {"x", "m, horizontal displacement l sin(theta)"},
                                          {"mode", "free | contact_right | contact_left"}};
  write_history_csv(results.fig4c, open("fig4c.csv"));
  write_json(open("fig4c.json"),
             sidecar("fig4c", history_columns,
                     {{"V0_m_per_s", settings.V0_of_history},
                      {"omega_rad_per_s", settings.omega_of_history},
                      {"window_s", {results.history_from, results.history_to}},
                      {"wall_position_m", results.wall_position},
                      {"slips", slips}}));
  write_history_csv(results.fig4d, open("fig4d.csv"));
  write_json(open("fig4d.json"),
             sidecar("fig4d", history_columns,
                     {{"V0_m_per_s", settings.V0_of_history},
                      {"omega_rad_per_s", settings.omega_of_history},
                      {"window_s", {results.zoom_from, results.zoom_to}},
                      {"wall_position_m", results.wall_position}}));
  nlohmann::json report = provenance;
  report["tolerances_m_per_s"] = report_tolerances();
  report["ranges"] = derived;
  report["slips"] = slips;
  report["wall_time_s"] = results.wall_time;
  write_json(open("report.json"), report);
  open("REPORT.md").stream() << markdown_report(results, settings, scene, provenance);

  run_files.commit();
}

}  // namespace impactlab
