#include <impactlab/api/compare.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include <impactlab/api/model_spec.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/platform/sample_median.hpp>

namespace impactlab {

namespace {

// impact times closer than this count as the same impact (s): far above the
// event location's error (~atol / |γ_N|), far below an impact interval
constexpr double same_time = 1e-6;

std::string field(double value) {
  if (std::isnan(value)) return "";
  return fmt::format("{:.17g}", value);
}

std::vector<ContactInterval> contact_intervals(const RunOutput& output) {
  std::vector<ContactInterval> intervals;
  bool open = false;
  ContactInterval current;
  double work_at_start = 0.0;
  for (const auto& e : output.events) {
    if (e.kind == EventKind::contact_start) {
      current = {e.wall, e.t, output.t_final, 0.0};
      work_at_start = std::isnan(e.friction_work) ? 0.0 : e.friction_work;
      open = true;
    } else if (e.kind == EventKind::contact_end && open) {
      current.t_end = e.t;
      current.friction_work = std::isnan(e.friction_work) ? 0.0 : e.friction_work - work_at_start;
      intervals.push_back(current);
      open = false;
    }
  }
  if (open) intervals.push_back(current);
  return intervals;
}

}  // namespace

std::vector<std::string> parse_model_list(std::string_view list) {
  std::vector<std::string> models;
  std::set<std::string> seen;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name(list.substr(start, comma - start));
    if (name.empty()) throw BadInput("models", std::string(list), "empty model name in the list");
    if (!seen.insert(name).second)
      throw BadInput("models", std::string(list), "model " + name + " is listed twice");
    models.push_back(name);
    start = comma + 1;
  }
  return models;
}

std::vector<std::string> scene_models(const Scene& scene) {
  std::vector<std::string> models;
  for (const auto& spec : oscillator_entry(scene.oscillator).schema->keys)
    if (spec.key == "model")
      for (auto choice : spec.choices) models.emplace_back(choice);
  return models;
}

Comparison compare_models(const Scene& scene, const std::vector<std::string>& models,
                          RunRequest request) {
  if (!scene.values.contains("model"))
    throw BadInput("oscillator", scene.oscillator, "this oscillator has no `model` key to compare");
  Comparison comparison;
  comparison.period = scene.forcing_period();
  request.sample_step = comparison.period;
  request.keep_events = true;
  for (const auto& model : models) {
    ModelRun run{model, scene, {}, {}, {}};
    apply_model(run.scene, model);
    run.output = run_of_scene(run.scene, request);
    for (const auto& e : run.output.events)
      if (e.kind == EventKind::impact) run.impacts.push_back(e);
    run.contacts = contact_intervals(run.output);
    comparison.runs.push_back(std::move(run));
  }
  return comparison;
}

void write_impacts_csv(std::ostream& out, const Comparison& comparison) {
  out << "k";
  std::size_t rows = 0;
  for (const auto& run : comparison.runs) {
    for (const char* column : {"t", "wall", "qdot_before", "qdot_after", "normal_impulse",
                               "tangential_velocity", "tangential_velocity_after"})
      out << ',' << column << '_' << run.model;
    rows = std::max(rows, run.impacts.size());
  }
  out << '\n';
  for (std::size_t k = 0; k < rows; ++k) {
    out << k;
    for (const auto& run : comparison.runs) {
      if (k >= run.impacts.size()) {
        out << ",,,,,,,";
        continue;
      }
      const EventRecord& e = run.impacts[k];
      out << ',' << field(e.t) << ',' << e.wall << ',' << field(e.qdot_before) << ','
          << field(e.qdot_after) << ',' << field(e.normal_impulse) << ','
          << field(e.tangential_velocity) << ',' << field(e.tangential_velocity_after);
    }
    out << '\n';
  }
}

void write_contacts_csv(std::ostream& out, const Comparison& comparison) {
  out << "model,k,wall,t_start,t_end,duration,friction_work\n";
  for (const auto& run : comparison.runs)
    for (std::size_t k = 0; k < run.contacts.size(); ++k) {
      const ContactInterval& c = run.contacts[k];
      out << run.model << ',' << k << ',' << c.wall << ',' << field(c.t_start) << ','
          << field(c.t_end) << ',' << field(c.t_end - c.t_start) << ',' << field(c.friction_work)
          << '\n';
    }
}

void write_section_csv(std::ostream& out, const Comparison& comparison) {
  out << "k,t";
  std::size_t rows = 0;
  for (const auto& run : comparison.runs) {
    out << ",q_" << run.model << ",qdot_" << run.model;
    rows = std::max(rows, run.output.samples.size());
  }
  out << '\n';
  for (std::size_t k = 0; k < rows; ++k) {
    const auto& first = comparison.runs.front().output;
    const double t = k < first.samples.size() ? first.samples[k].t
                                              : first.t0 + static_cast<double>(k) * comparison.period;
    out << k << ',' << field(t);
    for (const auto& run : comparison.runs) {
      if (k >= run.output.samples.size()) {
        out << ",,";
        continue;
      }
      out << ',' << field(run.output.samples[k].q) << ',' << field(run.output.samples[k].qdot);
    }
    out << '\n';
  }
}

nlohmann::json comparison_numbers(const Comparison& comparison) {
  nlohmann::json numbers = {{"period_s", comparison.period},
                            {"same_time_s", same_time},
                            {"models", nlohmann::json::object()},
                            {"pairs", nlohmann::json::array()}};
  for (const auto& run : comparison.runs) {
    double contact_time = 0.0, friction_work = 0.0;
    for (const auto& c : run.contacts) {
      contact_time += c.t_end - c.t_start;
      friction_work += c.friction_work;
    }
    std::vector<double> ratios;
    std::size_t sticking = 0;  // impacts whose impulse stuck (EventRecord::sticks)
    for (const auto& e : run.impacts) {
      if (std::isnan(e.tangential_velocity_after)) continue;
      sticking += e.sticks ? 1 : 0;
      if (std::fabs(e.tangential_velocity) > 1e-9)
        ratios.push_back(e.tangential_velocity_after / e.tangential_velocity);
    }
    numbers["models"][run.model] = {
        {"impacts", run.impacts.size()},
        {"contact_phases", run.contacts.size()},
        {"contact_time_s", contact_time},
        {"friction_work_J", friction_work},
        {"termination", to_string(run.output.termination)},
        {"t_final_s", run.output.t_final},
        {"steps", run.output.steps},
        {"wall_time_s", run.output.wall_time},
        {"section_points", run.output.samples.size()},
        {"sticking_impacts", sticking},
        {"tangential_ratio_median", ratios.empty() ? nlohmann::json(nullptr) : nlohmann::json(upper_median(ratios))},
        {"radius_m", run.scene.values.contains("radius") ? run.scene.number("radius") : 0.0},
        {"spin", run.scene.values.contains("spin") ? run.scene.text("spin") : ""},
    };
  }
  const ModelRun& reference = comparison.runs.front();
  for (std::size_t i = 1; i < comparison.runs.size(); ++i) {
    const ModelRun& other = comparison.runs[i];
    const std::size_t matched = std::min(reference.impacts.size(), other.impacts.size());
    std::size_t agree = 0;  // impacts matched in order with the same wall and time
    double max_dt = 0.0, max_dqdot = 0.0;
    for (; agree < matched; ++agree) {
      const EventRecord& a = reference.impacts[agree];
      const EventRecord& b = other.impacts[agree];
      if (a.wall != b.wall || std::fabs(a.t - b.t) > same_time) break;
      max_dt = std::max(max_dt, std::fabs(a.t - b.t));
      max_dqdot = std::max({max_dqdot, std::fabs(a.qdot_before - b.qdot_before),
                            std::fabs(a.qdot_after - b.qdot_after)});
    }
    const std::size_t points = std::min(reference.output.samples.size(), other.output.samples.size());
    double section_distance = 0.0;
    for (std::size_t k = 0; k < points; ++k)
      section_distance += std::hypot(reference.output.samples[k].q - other.output.samples[k].q,
                                     reference.output.samples[k].qdot - other.output.samples[k].qdot);
    numbers["pairs"].push_back({
        {"reference", reference.model},
        {"model", other.model},
        {"matched_impacts", matched},
        {"agreeing_impacts", agree},
        {"first_disagreement",
         agree < matched ? nlohmann::json(agree) : nlohmann::json(nullptr)},
        {"first_disagreement_t_s",
         agree < matched ? nlohmann::json(std::min(reference.impacts[agree].t, other.impacts[agree].t))
                         : nlohmann::json(nullptr)},
        {"max_abs_dt_agreeing_s", max_dt},
        {"max_abs_dqdot_agreeing", max_dqdot},
        {"section_points", points},
        {"section_mean_distance", points > 0 ? section_distance / static_cast<double>(points) : 0.0},
    });
  }
  return numbers;
}

std::string comparison_summary(const Comparison& comparison, const nlohmann::json& numbers) {
  const Scene& scene = comparison.runs.front().scene;
  std::string text = fmt::format(
      "# Model comparison: {}\n\n"
      "Scene `{}` ({}), {} forcing periods of T = {:.6g} s from t0 = {:.6g} s. "
      "Each model runs the same scene with only the key `model` changed.\n\n"
      "| model | impacts | contact phases | time in contact (s) | friction work (J) | "
      "median γ_T⁺/γ_T⁻ | impacts that stick | termination | wall time (s) |\n"
      "|---|---|---|---|---|---|---|---|---|\n",
      scene.name, scene.name, scene.oscillator,
      std::round((comparison.runs.front().output.t_end - comparison.runs.front().output.t0) /
                 comparison.period),
      comparison.period, comparison.runs.front().output.t0);
  for (const auto& run : comparison.runs) {
    const auto& m = numbers["models"][run.model];
    text += fmt::format("| {} | {} | {} | {:.6g} | {:.6g} | {} | {} | {} | {:.3f} |\n", run.model,
                        m["impacts"].get<std::size_t>(), m["contact_phases"].get<std::size_t>(),
                        m["contact_time_s"].get<double>(), m["friction_work_J"].get<double>(),
                        m["tangential_ratio_median"].is_null()
                            ? std::string("—")
                            : fmt::format("{:.4g}", m["tangential_ratio_median"].get<double>()),
                        m["tangential_ratio_median"].is_null()
                            ? std::string("—")
                            : std::to_string(m["sticking_impacts"].get<std::size_t>()),
                        m["termination"].get<std::string>(), m["wall_time_s"].get<double>());
  }
  text += "\n## Where they agree\n\n";
  for (const auto& pair : numbers["pairs"]) {
    const std::string a = pair["reference"], b = pair["model"];
    const std::size_t agree = pair["agreeing_impacts"], matched = pair["matched_impacts"];
    if (agree == 0 && matched > 0) {
      text += fmt::format(
          "- `{}` and `{}`: the impact sequences differ from the first impact (t = {:.6g} s). "
          "Mean distance of the {} strobe points {:.3g}.\n",
          a, b, pair["first_disagreement_t_s"].get<double>(),
          pair["section_points"].get<std::size_t>(), pair["section_mean_distance"].get<double>());
    } else if (pair["first_disagreement"].is_null()) {
      text += fmt::format(
          "- `{}` and `{}`: all {} impacts matched in order agree (same wall, times within "
          "{:.0e} s; largest time difference {:.3g} s, largest angular-velocity difference "
          "{:.3g}); mean distance of the {} strobe points {:.3g}.\n",
          a, b, matched, same_time, pair["max_abs_dt_agreeing_s"].get<double>(),
          pair["max_abs_dqdot_agreeing"].get<double>(), pair["section_points"].get<std::size_t>(),
          pair["section_mean_distance"].get<double>());
    } else {
      text += fmt::format(
          "- `{}` and `{}`: the first {} impacts agree (same wall, times within {:.0e} s; "
          "largest difference {:.3g} s); they separate at impact {} (t = {:.6g} s). Mean "
          "distance of the {} strobe points {:.3g}.\n",
          a, b, agree, same_time, pair["max_abs_dt_agreeing_s"].get<double>(), agree,
          pair["first_disagreement_t_s"].get<double>(), pair["section_points"].get<std::size_t>(),
          pair["section_mean_distance"].get<double>());
    }
  }
  text += "\n## Why they differ\n\n";
  for (const auto& run : comparison.runs) {
    if (run.model == "newton") {
      text += "- `newton` (Model N): one degree of freedom; θ̇⁺ = −e_n θ̇⁻ at every impact "
              "whatever the friction, which only splits the impulse; the bob's tangential "
              "velocity after an impact is fixed by the kinematics.\n";
    } else if (run.model == "paper") {
      text += "- `paper` (Model P): an impact whose normal law and the paper's tangential "
              "restitution e_t cannot hold together (its Eq. 25) is a sliding impact: the bob "
              "is held on the wall, sliding, until the normal force vanishes, and leaves with "
              "θ̇ = −e_n θ̇⁻ (docs/model-card.md); the held time and the late rebound shift "
              "the following impact times.\n";
    } else if (run.model == "rigid") {
      const double radius = run.scene.number("radius");
      const std::string spin = run.scene.text("spin");
      const double l = run.scene.number("l"), b = run.scene.number("b");
      if (radius == 0.0 && spin == "locked") {
        text += "- `rigid` with radius 0 and the spin locked reduces to Model N (the collision "
                "matrix has rank one, the Newton–Coulomb impulse slides with θ̇⁺ = −e_n θ̇⁻): "
                "differences are round-off of the different formulas.\n";
      } else {
        text += fmt::format(
            "- `rigid` with a ball of radius {} m, spin {}: the wall is reached at "
            "θ0 = asin((b − r)/l) = {:.6g} rad instead of asin(b/l) = {:.6g} rad",
            radius, spin, std::asin((b - radius) / l), std::asin(b / l));
        if (spin == "free")
          text += "; friction impulses change the ball's spin, so the tangential velocity after "
                  "an impact comes from the impulse mechanics (stick: γ_T⁺ = −e_t γ_T⁻; slide: the "
                  "friction impulse −μ s P_N acts on rod and ball together), and in contact the "
                  "ball may roll on the wall (stick) instead of sliding";
        else
          text += "; the locked ball adds I_b = (2/5) m r² to the rod's inertia";
        text += ".\n";
      }
    }
  }
  text += "\nImpact sequences of non-smooth systems depend sensitively on small differences "
          "(a shifted impact time changes the phase of the forcing at the next one), so two "
          "models that differ slightly separate after some impacts even where their attractors "
          "are alike: compare the strobe sections (compare_section.csv) for that.\n";
  return text;
}

std::vector<std::string> models_to_compare(const Scene& scene, const std::string& list,
                                           const std::function<void(const BadInput&)>& skipped) {
  if (!scene.values.contains("model"))
    throw BadInput("oscillator", scene.oscillator, "this oscillator has no `model` key to compare");
  if (!list.empty()) return parse_model_list(list);
  std::vector<std::string> accepted;
  for (const auto& model : scene_models(scene)) {
    Scene probe = scene;
    try {
      apply_override(probe, "model=" + model);
      RunRequest tiny;
      tiny.periods = 0.0;
      tiny.t_end = probe.number("t0") + 1e-9;
      tiny.keep_events = false;
      simulate(probe, tiny);
      accepted.push_back(model);
    } catch (const BadInput& bad) {
      if (skipped) skipped(bad);
    }
  }
  if (accepted.empty()) throw BadInput("models", "(default)", "the scene accepts no model");
  return accepted;
}

}  // namespace impactlab
