#include <impactlab/api/scene_jobs.hpp>

#include <algorithm>

#include <fmt/format.h>

#include <impactlab/api/job_options.hpp>
#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

RunOutput simulate(const Scene& scene, const RunRequest& request) {
  return run_of_scene(scene, request);
}

EventExtender event_extender(const Scene& scene) { return event_extender_of_scene(scene); }

EventColumns event_columns(const Scene& scene) { return event_columns_of_scene(scene); }

SectionResult poincare(const Scene& scene, const SectionRequest& request) {
  return sweep_target(scene).section(scene, request);
}

PeriodicResult periodic(const Scene& scene, const PeriodicRequest& request) {
  return periodic_orbit_of_scene(scene, request);
}

ContinuationJobResult continue_orbit(const Scene& scene, const ContinuationJob& job) {
  const SceneSchema& schema = *oscillator_entry(scene.oscillator).schema;
  const auto check_key = [&](const std::string& option, const std::string& key, double from,
                             double to) {
    const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                   [&](const KeySpec& k) { return k.key == key; });
    if (spec == schema.keys.end() || spec->is_text || key.starts_with("initial.") ||
        key.starts_with("integrator.") || key == "t0")
      throw BadInput(option, key,
                     fmt::format("not a numeric parameter of oscillator {}", schema.oscillator));
    refuse_unread_key(scene, schema, key, option);
    // both ends admissible (BadInput names the key and value otherwise)
    Scene probe = scene;
    for (double value : {from, to}) {
      probe.values[key] = value;
      validate(probe, schema);
    }
  };
  check_key("param", job.parameter, job.from, job.to);
  if (!job.second_parameter.empty()) {
    if (job.second_parameter == job.parameter)
      throw BadInput("param2", job.second_parameter,
                     "must differ from " + mention("param") + "'s key");
    check_key("param2", job.second_parameter, job.second_from, job.second_to);
  }
  ContinuationJobResult result = continuation_of_scene(scene, job);
  if (!result.available) throw BadInput("oscillator", scene.oscillator, result.note);
  if (result.branches.empty() ||
      result.branches[0].result.stop_reason == StopReason::start_not_converged) {
    const std::string detail =
        result.branches.empty() ? std::string() : result.branches[0].result.stop_detail;
    // a detail that names an option is its own remedy
    const std::string remedy =
        detail.find('`') != std::string::npos
            ? std::string()
            : fmt::format(" (try {}, {} or {})", mention("period"), mention("start"),
                          mention("transient"));
    throw BadInput("param", fmt::format("{}={}:{}", job.parameter, job.from, job.to),
                   fmt::format("no period-{} orbit converged at {} = {}{}{}", job.period,
                               job.parameter, job.from, detail.empty() ? "" : ": " + detail,
                               remedy));
  }
  // a curve type asked for that the branch has no located point of
  if (job.curve_type && !result.has_curve) {
    const auto& points = result.branches[0].result.points;
    const bool has_point = std::any_of(points.begin(), points.end(), [&](const BifurcationPoint& p) {
      return p.located && curve_type_of(p) == job.curve_type;
    });
    if (!has_point) {
      std::string located;
      for (const BifurcationPoint& p : points)
        if (p.located) located += (located.empty() ? "" : ", ") + std::string(type_name(p));
      throw BadInput("curve", std::string(to_string(*job.curve_type)),
                     fmt::format("the branch ({} from {} to {} at {} = {}) has no located point of "
                                 "this type (located: {})",
                                 job.parameter, job.from, job.to, job.second_parameter,
                                 job.second_from, located.empty() ? "none" : located));
    }
  }
  return result;
}

void set_continuation_section(ContinuationJob& job, const std::string& text,
                              const std::string& key) {
  const SectionSpec section = parse_section(text, key);
  if (section.kind == SectionKind::strobe) {
    job.phase = section.phase;
    job.impact_wall = 0;
    return;
  }
  if (section.kind != SectionKind::impact)
    throw BadInput(key, text, "continuation takes strobe[:PHASE] or impact:WALL");
  if (section.wall == 0)
    throw BadInput(key, text, "continuation on the impact section needs one wall: impact:+1 or impact:-1");
  job.impact_wall = section.wall;
}

SweepTarget sweep_target(const Scene& scene) {
  return {oscillator_entry(scene.oscillator).schema, &section_of_scene};
}

}  // namespace impactlab
