#include <impactlab/api/attractors_job.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include <fmt/format.h>

#include <impactlab/api/job_options.hpp>
#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

// the box keys whose corners are probed, at most (2^10 corners); the keys
// past them are checked by the runs themselves
constexpr std::size_t most_probed_keys = 10;

const KeySpec* numeric_key(const SceneSchema& schema, const std::string& key) {
  const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                 [&](const KeySpec& k) { return k.key == key; });
  return spec == schema.keys.end() || spec->is_text ? nullptr : &*spec;
}

// Whether the oscillator accepts `scene` as a start: its keys in range, and
// its system built from them (the pendulum refuses a start inside a wall, the
// ball one below the table). The refusal, where there is one.
std::optional<BadInput> refusal(const Scene& scene, const SceneSchema& schema) {
  try {
    validate(scene, schema);
    // a run of a millionth of a forcing period builds the system and
    // checks its initial state, at no cost worth counting
    RunRequest request;
    request.periods = 1e-6;
    request.keep_events = false;
    simulate(scene, request);
  } catch (const BadInput& bad) {
    return bad;
  }
  return std::nullopt;
}

// The first refusal among the corners of `box` in `scene` (every key at its
// from or its to).
std::optional<BadInput> corner_refusal(const Scene& scene, const SceneSchema& schema,
                                       const std::vector<BoxRange>& box) {
  const std::size_t keys = std::min(box.size(), most_probed_keys);
  for (std::size_t corner = 0; corner < (std::size_t{1} << keys); ++corner) {
    Scene probe = scene;
    for (std::size_t k = 0; k < keys; ++k)
      probe.values[box[k].key] = (corner >> k) & 1U ? box[k].to : box[k].from;
    if (auto bad = refusal(probe, schema)) return bad;
  }
  return std::nullopt;
}

// KEY=FROM:TO; BadInput (key `box`) if malformed.
BoxRange parse_box(const std::string& text) {
  const auto equals = text.find('=');
  const auto colon = equals == std::string::npos ? equals : text.find(':', equals + 1);
  if (equals == std::string::npos || equals == 0 || colon == std::string::npos ||
      text.find(':', colon + 1) != std::string::npos)
    throw BadInput("box", text, "expected KEY=FROM:TO");
  const auto number = [&](const std::string& part) {
    char* end = nullptr;
    const double value = std::strtod(part.c_str(), &end);
    if (part.empty() || *end != '\0' || !std::isfinite(value))
      throw BadInput("box", text, "FROM and TO must be finite numbers");
    return value;
  };
  BoxRange range;
  range.key = text.substr(0, equals);
  range.from = number(text.substr(equals + 1, colon - equals - 1));
  range.to = number(text.substr(colon + 1));
  return range;
}

std::string box_text(const BoxRange& range) {
  return fmt::format("{}={}:{}", range.key, range.from, range.to);
}

}  // namespace

std::vector<BoxRange> default_box(const Scene& scene, const SceneSchema& schema) {
  std::vector<BoxRange> box;
  for (const KeySpec& spec : schema.keys)
    if (!spec.is_text && spec.key.starts_with("initial.") &&
        unread_key_reason(scene, schema, std::string(spec.key)).empty())
      box.push_back({std::string(spec.key), 0.0, 0.0});
  if (box.empty())
    throw BadInput("box", "", fmt::format("oscillator {} has no initial-state key to sample: "
                                          "give {}", schema.oscillator, mention("box")));
  // each key's half-width h, halved where a corner is refused for that key:
  // both sides of v first; where no width is accepted (v on the edge of the
  // admissible states: a ball on the table), the upper side [v, v + h], then
  // the lower one [v − h, v]
  constexpr double narrowest = 0x1.0p-40;
  std::vector<double> half(box.size(), 1.0);
  std::vector<int> side(box.size(), 0);  // 0: both sides, +1: upper, −1: lower
  const auto lay_out = [&] {
    for (std::size_t k = 0; k < box.size(); ++k) {
      const double v = scene.number(box[k].key);
      box[k].from = side[k] > 0 ? v : v - half[k];
      box[k].to = side[k] < 0 ? v : v + half[k];
    }
  };
  for (;;) {
    lay_out();
    const auto bad = corner_refusal(scene, schema, box);
    if (!bad) return box;
    const auto refused = std::find_if(box.begin(), box.end(),
                                      [&](const BoxRange& r) { return r.key == bad->key(); });
    // a refusal naming another key (the scene's own start refused): the
    // scene is at fault, and says so
    if (refused == box.end()) throw *bad;
    const std::size_t k = static_cast<std::size_t>(refused - box.begin());
    half[k] /= 2.0;
    if (half[k] >= narrowest) continue;
    if (side[k] == -1) break;
    side[k] = side[k] == 0 ? 1 : -1;
    half[k] = 1.0;
  }
  throw BadInput("box", "", fmt::format("no range around the scene's initial state is accepted "
                                        "by oscillator {}: give {}",
                                        schema.oscillator, mention("box")));
}

std::vector<BoxRange> box_of_options(const std::vector<std::string>& options,
                                     const Scene& scene, const SceneSchema& schema) {
  std::vector<BoxRange> box;
  std::set<std::string> keys;
  for (const std::string& text : options) {
    BoxRange range = parse_box(text);
    if (numeric_key(schema, range.key) == nullptr)
      throw BadInput("box", text,
                     fmt::format("{} is not a numeric key of oscillator {}", range.key,
                                 schema.oscillator));
    refuse_unread_key(scene, schema, range.key, "box");
    if (!keys.insert(range.key).second)
      throw BadInput("box", text, fmt::format("{} is given twice", range.key));
    box.push_back(std::move(range));
  }
  if (box.empty()) return default_box(scene, schema);
  return box;
}

void refuse_box_corners(const Scene& scene, const SceneSchema& schema,
                        const std::vector<BoxRange>& box, const std::string& where) {
  if (const auto bad = corner_refusal(scene, schema, box)) {
    const auto refused = std::find_if(box.begin(), box.end(),
                                      [&](const BoxRange& r) { return r.key == bad->key(); });
    throw BadInput("box", refused == box.end() ? bad->key() : box_text(*refused),
                   fmt::format("the box leaves the states the oscillator accepts{} ({})",
                               where.empty() ? "" : " at " + where, bad->what()));
  }
}

SweepPlan make_attractors_plan(const AttractorsSpec& spec, const Scene& scene,
                               const SceneSchema& schema) {
  if (spec.samples < 1)
    throw BadInput("samples", std::to_string(spec.samples), "must be a whole number >= 1");
  for (const auto& [option, value] : {std::pair{"attractor_tol", spec.attractor_tolerance},
                                      std::pair{"match_tol", spec.match_tolerance}})
    if (!(value > 0.0) || !std::isfinite(value))
      throw BadInput(option, fmt::format("{}", value), "must be a finite number > 0");
  SweepSpec sweep;
  sweep.params = {spec.param};
  sweep.section = spec.section;
  sweep.lyapunov = spec.lyapunov;
  sweep.period_tolerance = spec.period_tolerance;
  sweep.max_period = spec.max_period;
  SweepPlan plan = make_sweep_plan(sweep, scene, schema);
  const SweepAxis& axis = plan.axes[0];
  // the samples' rows (samples.csv) sized against the scene's row budget
  const double rows = static_cast<double>(axis.count) * static_cast<double>(spec.samples);
  if (rows > scene.number("limits.max_rows"))
    throw BadInput("samples", std::to_string(spec.samples),
                   fmt::format("{} values x {} samples would write {:.3g} rows, over "
                               "limits.max_rows (raise it with `set` limits.max_rows=N)",
                               axis.count, spec.samples, rows));

  // the box: each key a numeric key the model reads, once, not the parameter
  std::vector<BoxRange> box = box_of_options(spec.box, scene, schema);
  for (std::size_t k = 0; k < box.size() && k < spec.box.size(); ++k)
    if (box[k].key == axis.name)
      throw BadInput("box", spec.box[k], "the key is the swept " + mention("param"));
  // every corner of the box accepted at both ends of the parameter
  for (const double value : {axis.from, axis.to}) {
    Scene end = scene;
    end.values[axis.name] = value;
    refuse_box_corners(end, schema, box, fmt::format("{} = {}", axis.name, value));
  }

  plan.follow_attractor = false;  // every sample from its own initial state
  // attractors are told apart by their section points: the scene's integrator
  plan.classification_integrator.reset();
  plan.classification_note =
      "the scene's integrator: attractors are told apart by their section points";
  plan.samples = spec.samples;
  plan.box = std::move(box);
  plan.seed = spec.seed;
  plan.attractor_tolerance = spec.attractor_tolerance;
  plan.match_tolerance = spec.match_tolerance;
  return plan;
}

nlohmann::json attractors_definition(const SweepPlan& plan, const Scene& scene,
                                     const SceneSchema& schema,
                                     const nlohmann::json& section_record) {
  nlohmann::json definition = sweep_definition(plan, scene, schema, section_record);
  nlohmann::json box = nlohmann::json::array();
  for (const BoxRange& range : plan.box)
    box.push_back({{"key", range.key},
                   {"unit", std::string(numeric_key(schema, range.key)->unit)},
                   {"from", range.from},
                   {"to", range.to}});
  definition["attractors"] = true;
  definition["samples"] = plan.samples;
  definition["box"] = box;
  definition["seed"] = plan.seed;
  definition["attractor_tolerance"] = plan.attractor_tolerance;
  definition["match_tolerance"] = plan.match_tolerance;
  return definition;
}

AttractorsTable attractors_table(const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                                 const std::map<SweepRecordKey, SweepRecord>& records) {
  AttractorsTable table;
  const SweepAxis& axis = plan.axes[0];
  // each value's samples in sample order (its tasks come in that order)
  std::vector<std::vector<const SweepRecord*>> by_value(axis.count);
  for (const auto& task : tasks)
    for (std::size_t p = 0; p < task.points.size(); ++p)
      by_value[task.points[p][0]].push_back(&records.at({task.id, static_cast<int>(p)}));
  // in increasing parameter values, whichever way the range is written
  for (int n = 0; n < axis.count; ++n) {
    const int i = axis.ascending() ? n : axis.count - 1 - n;
    table.values.push_back(
        attractors_at_value(i, axis.value(i), by_value[i], plan.attractor_tolerance));
  }
  table.events = follow_attractors(table.values, plan.match_tolerance);

  auto& rows = table.attractors;
  auto& points = table.points;
  auto& samples = table.samples;
  samples.box.resize(plan.box.size());
  const double none = std::nan("");
  for (AttractorsAtValue& at : table.values) {
    if (at.unclassified > 0) {
      const double f = static_cast<double>(at.unclassified) / at.samples;
      rows.value.push_back(at.value);
      rows.id.push_back(0);
      rows.period.push_back(0);
      rows.impacts_per_cycle.push_back(0);
      rows.contact.push_back(0);
      rows.samples.push_back(at.unclassified);
      for (auto* column : {&rows.impacts_per_period, &rows.contact_phases_per_period,
                           &rows.min_impact_speed, &rows.q, &rows.qdot, &rows.lyapunov})
        column->push_back(none);
      rows.fraction.push_back(f);
      rows.fraction_error.push_back(fraction_error(f, at.samples));
    }
    std::vector<const SampledAttractor*> by_id;
    for (const SampledAttractor& a : at.attractors) by_id.push_back(&a);
    std::sort(by_id.begin(), by_id.end(),
              [](const SampledAttractor* a, const SampledAttractor* b) { return a->id < b->id; });
    for (const SampledAttractor* a : by_id) {
      rows.value.push_back(at.value);
      rows.id.push_back(a->id);
      rows.period.push_back(a->period);
      rows.impacts_per_cycle.push_back(a->impacts_per_cycle);
      rows.contact.push_back(a->contact ? 1 : 0);
      rows.samples.push_back(a->samples);
      rows.impacts_per_period.push_back(a->impacts_per_period);
      rows.contact_phases_per_period.push_back(a->contact_phases_per_period);
      rows.min_impact_speed.push_back(a->min_impact_speed);
      rows.q.push_back(a->point[0]);
      rows.qdot.push_back(a->point[1]);
      rows.lyapunov.push_back(a->lyapunov);
      rows.fraction.push_back(a->fraction);
      rows.fraction_error.push_back(a->fraction_error);
      for (std::size_t k = 0; k < a->cycle.size(); ++k) {
        points.value.push_back(at.value);
        points.id.push_back(a->id);
        points.k.push_back(static_cast<int>(k));
        points.q.push_back(a->cycle[k][0]);
        points.qdot.push_back(a->cycle[k][1]);
      }
    }
    // the samples of this value, in sample order
    const auto& records_here = by_value[at.index];
    for (std::size_t s = 0; s < records_here.size(); ++s) {
      const SweepRecord& r = *records_here[s];
      const int local = at.sample_attractor[s];
      samples.value.push_back(at.value);
      samples.sample.push_back(r.index[1]);
      for (std::size_t k = 0; k < plan.box.size(); ++k)
        samples.box[k].push_back(
            box_value(plan.box[k], plan.seed, r.index[0], r.index[1], static_cast<int>(k)));
      samples.attractor.push_back(local == 0 ? 0 : at.attractors[local - 1].id);
      samples.period.push_back(r.classification.period);
      samples.impacts_per_period.push_back(r.classification.impacts_per_period);
      samples.contact.push_back(r.classification.contact ? 1 : 0);
      samples.termination.push_back(r.result.termination);
      samples.transient_end.push_back(r.result.transient_end);
    }
  }
  return table;
}

nlohmann::json attractor_events_record(const AttractorsTable& table, const SweepPlan& plan) {
  // the value at each index, and the one before it in parameter order
  std::map<int, double> value_at, previous_value;
  for (std::size_t v = 0; v < table.values.size(); ++v) {
    value_at[table.values[v].index] = table.values[v].value;
    if (v > 0) previous_value[table.values[v].index] = table.values[v - 1].value;
  }
  nlohmann::json events = nlohmann::json::array();
  for (const AttractorEvent& e : table.events) {
    nlohmann::json event = {{"type", std::string(to_string(e.change))},
                            {"attractor", e.attractor},
                            {"from_value", previous_value.at(e.index)},
                            {"to_value", value_at.at(e.index)}};
    if (e.change == AttractorChange::merge) event["into"] = e.other;
    if (e.change == AttractorChange::split) event["split_from"] = e.other;
    events.push_back(event);
  }
  return {{"parameter", plan.axes[0].name},
          {"events", events},
          {"meaning",
           {{"appear", "an attractor found at to_value and matched to none at from_value"},
            {"vanish", "an attractor found at from_value and matched to none at to_value"},
            {"merge", "an attractor at from_value whose nearest attractor at to_value (within "
                      "match_tolerance) continues another id: `into`"},
            {"split", "an attractor at to_value whose nearest attractor at from_value (within "
                      "match_tolerance) continues as another id: `split_from`"},
            {"from_value", "the last parameter value before the change"},
            {"to_value", "the first parameter value after it"}}}};
}

std::string attractors_line(const AttractorsTable& table) {
  int most = 0;
  for (const auto& at : table.values)
    for (const auto& a : at.attractors) most = std::max(most, a.id);
  std::map<std::string_view, int> by_change;
  for (const AttractorEvent& e : table.events) ++by_change[to_string(e.change)];
  std::string changes;
  for (const auto& [change, count] : by_change)
    changes += fmt::format("{}{} {}", changes.empty() ? "" : ", ", change, count);
  return fmt::format("{} attractors followed over {} values; events: {}", most,
                     table.values.size(), changes.empty() ? "none" : changes);
}

}  // namespace impactlab
