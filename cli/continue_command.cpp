// `impactlab continue`: pseudo-arclength continuation of a period-n orbit in
// one scene key, with its bifurcations and grazing points located
// (analysis/continuation.hpp); writes branch.csv, points.csv and
// continuation.json (units, provenance, why each branch stopped).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>

#include <fmt/format.h>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/api/continuation_job.hpp>
#include <impactlab/api/every_orbit_continuation.hpp>
#include <impactlab/api/grazing_record.hpp>
#include <impactlab/api/periodic_job.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "interrupted_runs.hpp"
#include "commands.hpp"
#include "section_options.hpp"
#include "table_options.hpp"
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>

namespace impactlab::cli {

namespace {

// " (detail)" after a stop reason, or nothing where there is no detail
std::string in_brackets(const std::string& detail) {
  return detail.empty() ? std::string() : " (" + detail + ")";
}

// The values as given; their defaults come from the "continue" option table.
struct ContinueCommandOptions {
  SceneOptions scene;
  ContinueOptions job;     // the job's own options (api/continuation_job.hpp)
  bool plot = false;
  std::string with_sweep;  // a sweep's bifurcation.csv drawn under the branch
};

// The columns of an orbit's state: q,qdot, then state3 ... stateN (a model
// file's further states, in its order).
std::string state_header(std::size_t dimension) {
  std::string header = "q,qdot";
  for (std::size_t k = 3; k <= dimension; ++k) header += fmt::format(",state{}", k);
  return header;
}
std::string state_fields(const OrbitPoint& state, std::size_t dimension) {
  std::string fields;
  for (std::size_t k = 0; k < dimension; ++k)
    fields += (k == 0 ? "" : ",") + csv_field(k < state.size() ? state[k] : NAN);
  return fields;
}
// multiplier1_re,multiplier1_im,...,multiplierN_im[,multiplier1_abs,...,multiplierN_abs]
std::string multiplier_header(std::size_t dimension, bool with_modulus) {
  std::string header;
  for (std::size_t k = 1; k <= dimension; ++k)
    header += fmt::format("{}multiplier{}_re,multiplier{}_im", k == 1 ? "" : ",", k, k);
  if (with_modulus)
    for (std::size_t k = 1; k <= dimension; ++k) header += fmt::format(",multiplier{}_abs", k);
  return header;
}
std::string multiplier_fields(const std::vector<std::complex<double>>& multipliers,
                              std::size_t dimension, bool with_modulus) {
  std::string fields;
  const auto at = [&](std::size_t k) {
    return k < multipliers.size() ? multipliers[k] : std::complex<double>(NAN, NAN);
  };
  for (std::size_t k = 0; k < dimension; ++k)
    fields += (k == 0 ? "" : ",") + csv_field(at(k).real()) + ',' + csv_field(at(k).imag());
  if (with_modulus)
    for (std::size_t k = 0; k < dimension; ++k) fields += ',' + csv_field(std::abs(at(k)));
  return fields;
}

void write_branch_csv(AtomicFile& file, const std::string& name, std::size_t dimension,
                      const std::vector<ContinuedBranch>& branches) {
  auto& out = file.stream();
  out << name << ',' << state_header(dimension)
      << ",period,branch,impacts,contact_phases,stable," << multiplier_header(dimension, true)
      << ",min_impact_speed,min_flight_gap,newton_iterations\n";
  for (std::size_t b = 0; b < branches.size(); ++b)
    for (const BranchPoint& p : branches[b].result.branch)
      out << csv_field(p.parameter) << ',' << state_fields(p.state, dimension) << ','
          << branches[b].period << ',' << b << ',' << p.impacts << ',' << p.contact_phases << ','
          << (p.stable ? 1 : 0) << ',' << multiplier_fields(p.multipliers, dimension, true)
          << ',' << csv_field(std::isfinite(p.min_impact_speed) ? p.min_impact_speed : NAN) << ','
          << csv_field(std::isfinite(p.min_flight_gap) ? p.min_flight_gap : NAN) << ','
          << p.newton_iterations << '\n';
}

void write_points_csv(AtomicFile& file, const std::string& name, std::size_t dimension,
                      const std::vector<ContinuedBranch>& branches) {
  auto& out = file.stream();
  out << "type," << name << ',' << state_header(dimension) << ",period,branch,"
      << multiplier_header(dimension, false)
      << ",error_estimate,located,graze_time,graze_witness,note," << grazing_csv_header << '\n';
  for (std::size_t b = 0; b < branches.size(); ++b)
    for (const BifurcationPoint& p : branches[b].result.points)
      out << type_name(p) << ',' << csv_field(p.parameter) << ','
          << state_fields(p.state, dimension)
          << ',' << branches[b].period << ',' << b << ','
          << multiplier_fields(p.multipliers, dimension, false) << ','
          << csv_field(p.error_estimate) << ',' << (p.located ? 1 : 0) << ','
          << csv_field(p.graze_time) << ',' << p.graze_witness << ",\"" << p.note << "\","
          << grazing_csv_fields(p) << '\n';
}

// every curve, one row per point: the first branch's, then (--switch) each
// doubled branch's, told apart by the branch and period columns
void write_curve_csv(AtomicFile& file, const std::string& name1, const std::string& name2,
                     std::size_t dimension, const std::vector<BranchCurve>& curves) {
  auto& out = file.stream();
  out << name1 << ',' << name2 << ',' << state_header(dimension) << ','
      << multiplier_header(dimension, true)
      << ",graze_time,impacts,newton_iterations,branch,period,type,start\n";
  for (const BranchCurve& curve : curves)
    for (const CurvePoint& p : curve.curve.curve)
      out << csv_field(p.p1) << ',' << csv_field(p.p2) << ',' << state_fields(p.state, dimension)
          << ',' << multiplier_fields(p.multipliers, dimension, true) << ','
          << csv_field(p.graze_time) << ',' << p.impacts << ',' << p.newton_iterations << ','
          << curve.branch << ',' << curve.period << ',' << to_string(curve.curve.type) << ','
          << start_name(curve) << '\n';
}

// the codimension-two points of every curve, in the curves' order
void write_curve_points_csv(AtomicFile& file, const std::string& name1, const std::string& name2,
                            std::size_t dimension, const std::vector<BranchCurve>& curves) {
  auto& out = file.stream();
  out << "type," << name1 << ',' << name2 << ',' << state_header(dimension) << ','
      << multiplier_header(dimension, false)
      << ",error_estimate,located,graze_time,branch,period,note\n";
  for (const BranchCurve& curve : curves)
    for (const CodimensionTwoPoint& p : curve.curve.points)
      out << to_string(p.type) << ',' << csv_field(p.p1) << ',' << csv_field(p.p2) << ','
          << state_fields(p.state, dimension) << ','
          << multiplier_fields(p.multipliers, dimension, false) << ','
          << csv_field(p.error_estimate) << ',' << (p.located ? 1 : 0) << ','
          << csv_field(p.graze_time) << ',' << curve.branch << ',' << curve.period << ",\""
          << p.note << "\"\n";
}

int run_continue(const ContinueCommandOptions& command_options,
                 const std::vector<std::string>& command_line) {
  const ContinueOptions& options = command_options.job;
  const Scene scene = command_options.scene.load();
  const ContinuationJob job = continuation_job(options);
  const KeyRange range{job.parameter, job.from, job.to};
  const bool two_parameter = !job.second_parameter.empty();
  const KeyRange range2{job.second_parameter, job.second_from, job.second_to};
  const std::string& with_sweep = command_options.with_sweep;
  if (!with_sweep.empty() && !std::filesystem::is_regular_file(with_sweep))
    throw BadInput("with_sweep", with_sweep,
                   two_parameter ? "no such file (a 2D sweep's classes.csv)"
                                 : "no such file (a sweep's bifurcation.csv)");
  const SectionSpec section = parse_section(options.section, "section");

  const auto directory = command_options.scene.output_directory();
  const auto started = std::chrono::steady_clock::now();
  // with --all, every orbit periodic --all finds at FROM, each continued
  std::optional<EveryOrbitContinuation> every;
  if (options.all) every = continue_every_orbit(scene, job, options);
  const ContinuationJobResult result = every ? every->continuation : continue_orbit(scene, job);
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  // branch.csv, points.csv, continuation.json (and the curve's files),
  // committed together
  RunFiles run_files = open_run_files(directory);
  write_branch_csv(run_files.add("branch.csv"), range.name, result.dimension, result.branches);
  write_points_csv(run_files.add("points.csv"), range.name, result.dimension, result.branches);

  nlohmann::json branches = nlohmann::json::array();
  for (std::size_t b = 0; b < result.branches.size(); ++b) {
    const ContinuedBranch& branch = result.branches[b];
    branches.push_back({{"period", branch.period},
                        {"points", branch.result.branch.size()},
                        {"bifurcations", branch.result.points.size()},
                        {"stop_reason", to_string(branch.result.stop_reason)},
                        {"stop_detail", branch.result.stop_detail},
                        {"map_evaluations", branch.result.map_evaluations}});
    if (every) branches.back()["orbit"] = every->branch_orbit[b];
  }
  nlohmann::json document = {
      {"impactlab_version", IMPACTLAB_VERSION},
      {"command", command_line},
      {"created_utc", utc_now()},
      {"scene", scene_record(scene)},
      {"request",
       {{"parameter", range.name},
        {"from", range.from},
        {"to", range.to},
        {"period", options.period},
        {"section", to_string(section)},
        {"transient_periods", options.transient},
        {"switch", options.switch_doubling},
        {"tolerance", options.tolerance},
        {"max_step", options.max_step},
        {"start", options.start}}},
      {"method",
       "pseudo-arclength continuation of the fixed point of the n-fold stroboscopic map (or "
       "of the impact map of one wall, state (impact phase, rate before the impact)); "
       "dF/dx from the saltation-corrected monodromy, dF/dp by a central difference; fold, "
       "period doubling and Neimark-Sacker located by TOMS 748 on the arclength; grazing "
       "solved as an extended system (zero gap, zero normal velocity)"},
      {"columns",
       {{"branch.csv",
         {{range.name, "the continued scene key (its unit in scene.units)"},
          {"q, qdot", section.kind == SectionKind::impact
                          ? "the orbit's state on the impact section: q the forcing phase "
                            "omega t mod 2 pi of the impact (rad), qdot the rate just before it"
                          : "the orbit's state on the section (main coordinate and its rate)"},
          {"state3...", "a model file with more states: its further states, in its order; the "
                        "rigid pendulum with the spin free: the ball's spin rate (rad/s)"},
          {"period", "forcing periods of the orbit"},
          {"branch", "0: the first branch; k: the k-th doubled branch (--switch)"},
          {"impacts", "impacts per orbit period"},
          {"stable", "1 if every Floquet multiplier lies inside the unit circle (a held "
                     "neutral component's multiplier 1 aside)"},
          {"multiplier*", "the N Floquet multipliers (N = 2, a model file's states, 3 for "
                          "the rigid pendulum with the spin free), largest modulus first"},
          {"min_flight_gap", "smallest wall gap in flight between impacts (q's unit)"},
          {"min_impact_speed", "smallest normal approach speed of an impact"}}},
        {"points.csv",
         {{"type", "fold, branch_point, period_doubling, neimark_sacker, grazing, contact_onset, "
                  "contact_end, stick_onset, stick_end (an impact starts or stops sticking: the "
                  "rigid pendulum's friction cone), contact_boundary (the pendulum's V0*omega = g), "
                  "chatter_onset (a chatter into contact stops completing)"},
          {"error_estimate", "bound on the error of the parameter value"},
          {"graze_time", "grazing: time after the section at which the wall is touched (0 "
                         "where the impact section's own impact grazes)"},
          {"scenario", "grazing: what its normal form predicts past the graze (grazing.json's "
                       "scenario; unavailable where it could not be computed)"},
          {"impacting_side", "grazing: +1 or -1, the sign of p - p_g where the orbit impacts"},
          {"impact_speed_coefficient", "grazing: c, the first impact past the graze at normal "
                                       "speed c sqrt|p - p_g| (the gap's rate unit)"},
          {"period_one_speed_slope", "grazing: the period-1 impacting orbit born there, "
                                     "impact speed slope |p - p_g|, on period_one_side"}}}}},
      {"branches", branches},
      {"wall_time_s", wall_time},
  };
  // --all: the orbits found at FROM (periodic --all's record) and those not continued
  if (every) {
    const nlohmann::json found = periodic_orbits_record(scene, every->orbits);
    document["all"] = {{"request", found["request"]},
                       {"starts", found["starts"]},
                       {"orbits", found["orbits"]},
                       {"not_continued", every->not_continued},
                       {"note", "each branch's `orbit` is the id of the orbit it continues, "
                                "found at the start of the range; an orbit on a branch "
                                "already continued is not continued again (not_continued)"}};
  }
    // a component held at its start value (analysis/neutral_component.hpp)
  if (result.neutral)
    document["neutral_component"] = {
        {"index", result.neutral->index + 1},
        {"value", result.neutral->value},
        {"note", "the map is neutral along this state component (multiplier 1, a family of "
                 "orbits): held at its start value, its multiplier listed with the others"}};
  write_json(run_files.add("continuation.json"), document);
  // grazing.json: an entry per grazing point, in points.csv's order
  nlohmann::json grazing_points = nlohmann::json::array();
  int row = 0;
  for (std::size_t b = 0; b < result.branches.size(); ++b)
    for (const BifurcationPoint& p : result.branches[b].result.points) {
      if (p.type == BifurcationType::grazing)
        grazing_points.push_back(grazing_record(p, range.name, row, static_cast<int>(b),
                                                result.branches[b].period));
      ++row;
    }
  const bool grazing = !grazing_points.empty();
  if (grazing)
    write_json(run_files.add("grazing.json"),
               {{"impactlab_version", IMPACTLAB_VERSION},
                {"command", command_line},
                {"created_utc", utc_now()},
                {"scene", scene_record(scene)},
                {"parameter", range.name},
                {"method",
                 "Nordmark's zero-time discontinuity map at the touch (leading and next order), "
                 "composed with the virtual orbit's flow into the normal form of the "
                 "stroboscopic map on the section through the touch; its scenario from "
                 "iterating it at 25 distances past the graze and from the eigenvalue rule "
                 "(docs/analysis.md, \"Discontinuity map and normal form at a grazing point\")"},
                {"units",
                 {{"parameter", "the scene key's (scene.units)"},
                  {"state", "the tangent state's (q, qdot, ...)"},
                  {"gap", "the touched witness's (length, or rad for the pendulum)"},
                  {"speeds", "the gap's rate (gap unit / s)"},
                  {"time", "s"}}},
                {"fields", grazing_fields()},
                {"points", grazing_points}});
  if (two_parameter) {
    // the curves: the first branch's, then each doubled branch's (--switch)
    std::vector<BranchCurve> curves = {
        {0, options.period, result.has_curve, result.curve, result.curve_note}};
    for (const BranchCurve& doubled : result.doubled_curves)
      if (doubled.has_curve) curves.push_back(doubled);
    for (const BranchCurve& switched : result.switched_curves)
      if (switched.has_curve) curves.push_back(switched);
    nlohmann::json curve_list = nlohmann::json::array();
    for (const BranchCurve& curve : result.doubled_curves)
      curve_list.push_back({{"branch", curve.branch},
                            {"period", curve.period},
                            {"type", curve.has_curve ? to_string(curve.curve.type) : ""},
                            {"points", curve.curve.curve.size()},
                            {"stop_reason", curve.has_curve ? to_string(curve.curve.stop_reason)
                                                            : "no_start_point"},
                            {"stop_detail", curve.has_curve ? curve.curve.stop_detail : curve.note},
                            {"codimension_two_points", curve.curve.points.size()},
                            {"map_evaluations", curve.curve.map_evaluations}});
    nlohmann::json switched_list = nlohmann::json::array();
    for (const BranchCurve& curve : result.switched_curves)
      switched_list.push_back({{"start", start_name(curve)},
                               {"type", curve.has_curve ? to_string(curve.curve.type) : ""},
                               {"points", curve.curve.curve.size()},
                               {"stop_reason", curve.has_curve
                                                   ? to_string(curve.curve.stop_reason)
                                                   : "no_start_point"},
                               {"stop_detail", curve.has_curve ? curve.curve.stop_detail
                                                               : curve.note},
                               {"map_evaluations", curve.curve.map_evaluations}});
    write_curve_csv(run_files.add("curve.csv"), range.name, range2.name, result.dimension,
                    curves);
    write_curve_points_csv(run_files.add("curve_points.csv"), range.name, range2.name,
                           result.dimension, curves);
    const nlohmann::json curve_document = {
        {"impactlab_version", IMPACTLAB_VERSION},
        {"command", command_line},
        {"created_utc", utc_now()},
        {"scene", scene_record(scene)},
        {"request",
         {{"parameter", range.name},
          {"from", range.from},
          {"to", range.to},
          {"parameter2", range2.name},
          {"from2", range2.from},
          {"to2", range2.to},
          {"curve", options.curve.empty() ? "first located" : options.curve},
          {"period", options.period},
          {"switch", options.switch_doubling},
          {"section", to_string(section)},
          {"tolerance", options.tolerance}}},
        {"type", result.has_curve ? to_string(result.curve.type) : ""},
        {"points", result.curve.curve.size()},
        {"stop_reason", result.has_curve ? to_string(result.curve.stop_reason) : "no_start_point"},
        {"stop_detail", result.has_curve ? result.curve.stop_detail : result.curve_note},
        {"map_evaluations", result.curve.map_evaluations},
        {"codimension_two_points", result.curve.points.size()},
        {"doubled_curves", curve_list},
        {"switched_curves", switched_list},
        {"method",
         "pseudo-arclength continuation in (q, qdot, p1, p2) of the orbit condition "
         "P^n(x) = x with det(M - I) = 0 (fold), det(M + I) = 0 (period doubling), zero gap "
         "and zero gap rate at t_g with the wall's contacts suppressed near t_g (grazing; t_g is "
         "an unknown too), or a zero push into the wall on the mass at rest where its contact "
         "phase lands (contact onset and end); the branch is run first at p2 = from2 and the "
         "curve starts at its first located point of the type"},
        {"columns",
         {{range.name, "the first scene key (its unit in scene.units)"},
          {range2.name, "the second scene key (its unit in scene.units)"},
          {"q, qdot", section.kind == SectionKind::impact
                          ? "the orbit's state on the impact section at the curve point: q the "
                            "forcing phase omega t mod 2 pi of the impact (rad), qdot the rate "
                            "just before it (a grazing of that impact: the touch)"
                          : "the orbit's state on the section at the curve point"},
          {"multiplier*", "Floquet multipliers of the orbit at the point"},
          {"graze_time", "grazing: time after the section at which the wall is touched (s; 0 "
                         "where the impact section's own impact grazes)"},
          {"impacts", "impacts per orbit period (a grazing point's touch not counted)"},
          {"branch", "the branch the curve starts from: 0, then k for the k-th doubled one "
                     "(--switch; doubled_curves)"},
          {"period", "forcing periods of that branch's orbit"},
          {"type", "the curve's type: fold, period_doubling, grazing, contact_onset, "
                   "contact_end, contact_boundary, neimark_sacker or chatter_onset"},
          {"start", "branch: the curve starts at a point located on the branch; "
                    "grazing_period_doubling or grazing_fold: it runs through that "
                    "codimension-two point of the first curve (--switch; switched_curves), "
                    "from the point towards the second parameter's FROM"}}},
        {"curve_points_columns",
           {{"type", "grazing_period_doubling or grazing_fold: on a grazing curve, where the "
                     "virtual orbit (the orbit through the graze) has a multiplier -1 or +1, "
                     "i.e. where a period-doubling or fold curve of that orbit meets the "
                     "grazing curve (on a period-doubling or fold curve: where it runs into "
                     "the graze, solved with the grazing system; the curve ends there); "
                     "grazing_scenario_change: where its dominant multiplier "
                     "passes 1/4 or 2/3, the eigenvalue rule's thresholds, or an impact's "
                     "kick on the later gaps (K or a kick gap e_k) changes sign, so that the "
                     "predicted scenario past the graze changes (note); cusp: on a fold curve, "
                     "where its tangent has no parameter component (two folds meet); "
                     "resonance_1_1, resonance_1_2: on a Neimark-Sacker curve, where the pair "
                     "on the unit circle meets at +1 or -1; degenerate_period_doubling: on a "
                     "period-doubling curve, where the flip's cubic coefficient is zero; "
                     "located by TOMS 748 on the curve's arclength"},
            {"error_estimate", "bound on the error of both parameter values (each in its "
                               "own unit; the larger)"},
            {"located", "1: located; 0: detected between two curve points only (note)"},
            {"graze_time", "time after the section at which the wall is touched (s)"},
            {"branch, period", "as in curve.csv"}}},
        {"wall_time_s", wall_time},
    };
    write_json(run_files.add("curve.json"), curve_document);
  }
  run_files.commit();

  if (command_options.plot || !with_sweep.empty()) {
    std::vector<std::string> names = {range.name,
                                      std::string(scene_schema(scene).main_coordinate)};
    if (!with_sweep.empty() && !two_parameter) names.push_back(with_sweep);
    plot_with_python("continuation", directory / "branch.csv", directory / "continuation.png",
                     names);
    if (grazing && !two_parameter) {
      std::vector<std::string> grazing_names = {range.name};
      if (!with_sweep.empty()) grazing_names.push_back(with_sweep);
      plot_with_python("grazing", directory / "grazing.json", directory / "grazing.png",
                       grazing_names);
    }
    if (two_parameter) {
      std::vector<std::string> curve_names = {range.name, range2.name};
      if (!with_sweep.empty()) curve_names.push_back(with_sweep);
      plot_with_python("curve", directory / "curve.csv", directory / "curve.png", curve_names);
    }
  }
  if (!command_options.scene.quiet) {
    for (const ContinuedBranch& branch : result.branches) {
      std::cout << fmt::format("period-{} branch: {} points, stopped: {}{}\n", branch.period,
                               branch.result.branch.size(), to_string(branch.result.stop_reason),
                               in_brackets(branch.result.stop_detail));
      for (const BifurcationPoint& p : branch.result.points)
      {
        std::cout << fmt::format("  {} at {} = {:.12g} (error {:.2g}){}\n", type_name(p),
                                 range.name,
                                 p.parameter, p.error_estimate, p.note.empty() ? "" : ": " + p.note);
        if (p.normal_form && p.normal_form->available)
          std::cout << fmt::format(
              "    normal form: {} for {} {} {:.12g} (impact speed {:.4g} sqrt|{} - {:.12g}|)\n",
              to_string(p.normal_form->scenario), range.name,
              p.normal_form->impacting_side > 0 ? ">" : "<", p.parameter,
              p.normal_form->root_coefficient, range.name, p.parameter);
      }
    }
    if (two_parameter) {
      if (result.has_curve)
        std::cout << fmt::format("{} curve in ({}, {}): {} points, stopped: {}{}\n",
                                 to_string(result.curve.type), range.name, range2.name,
                                 result.curve.curve.size(), to_string(result.curve.stop_reason),
                                 in_brackets(result.curve.stop_detail));
      else
        std::cout << "no curve: " << result.curve_note << '\n';
      for (const CodimensionTwoPoint& p : result.curve.points)
        std::cout << fmt::format("  {} at {} = {:.12g}, {} = {:.12g} (error {:.2g}){}\n",
                                 to_string(p.type), range.name, p.p1, range2.name, p.p2,
                                 p.error_estimate, p.note.empty() ? "" : ": " + p.note);
      for (const BranchCurve& switched : result.switched_curves) {
        if (switched.has_curve)
          std::cout << fmt::format("  {} curve through the {} point: {} points, stopped: {}{}\n",
                                   to_string(switched.curve.type), start_name(switched),
                                   switched.curve.curve.size(),
                                   to_string(switched.curve.stop_reason),
                                   in_brackets(switched.curve.stop_detail));
        else
          std::cout << fmt::format("  no curve through the {} point: {}\n",
                                   start_name(switched), switched.note);
      }
      for (const BranchCurve& doubled : result.doubled_curves) {
        if (doubled.has_curve)
          std::cout << fmt::format("  period-{} branch's {} curve: {} points, stopped: {}{}\n",
                                   doubled.period, to_string(doubled.curve.type),
                                   doubled.curve.curve.size(),
                                   to_string(doubled.curve.stop_reason),
                                   in_brackets(doubled.curve.stop_detail));
        else
          std::cout << fmt::format("  period-{} branch: no curve: {}\n", doubled.period,
                                   doubled.note);
      }
    }
    std::cout << "wrote " << (directory / "branch.csv").string() << ", points.csv, continuation.json"
              << (grazing ? ", grazing.json" : "")
              << (two_parameter ? ", curve.csv, curve_points.csv, curve.json" : "") << '\n';
  }
  return exit_done;
}

}  // namespace

Command add_continue_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "continue",
      "continue a period-n orbit in one parameter (pseudo-arclength), locating folds, period "
      "doublings, Neimark-Sacker and grazing points");
  auto options = std::make_shared<ContinueCommandOptions>();
  ContinueOptions& job = options->job;
  TableOptions table(*command, "continue");
  options->scene.add_scene(table);
  table.add("param", job.param);
  table.add("param2", job.param2);
  table.add("curve", job.curve);
  table.add("period", job.period);
  table.add("section", job.section);
  table.add("switch", job.switch_doubling);
  table.add("start", job.start);
  table.add("transient", job.transient);
  table.add("max_points", job.max_points);
  table.add("tolerance", job.tolerance);
  table.add("max_step", job.max_step);
  table.add("all", job.all);
  table.add("starts", job.starts);
  table.add("box", job.box);
  table.add("seed", job.seed);
  table.add("no_normal_forms", job.no_normal_forms);
  table.add("plot", options->plot);
  table.add("with_sweep", options->with_sweep);
  return {command,
          [options](const std::vector<std::string>& command_line) {
            return run_continue(*options, command_line);
          },
          "continue"};
}

}  // namespace impactlab::cli
