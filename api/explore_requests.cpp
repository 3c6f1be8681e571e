#include <impactlab/api/explore_requests.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include <impactlab/analysis/sweep.hpp>
#include <impactlab/api/periodic_job.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/sweep_job.hpp>
#include <impactlab/core/event_sink.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene_file.hpp>

namespace impactlab {

namespace {

using nlohmann::json;

// a bound of a schema's range, or null where it is none (±1e308; JSON has no infinities)
json bound(double value) { return std::abs(value) >= 1e308 ? json(nullptr) : json(value); }

// the shortest text that reads back as the same double
std::string exact(double value) { return fmt::format("{}", value); }

const KeySpec* find_key(const SceneSchema& schema, std::string_view key) {
  const auto found = std::find_if(schema.keys.begin(), schema.keys.end(),
                                  [&](const KeySpec& spec) { return spec.key == key; });
  return found == schema.keys.end() ? nullptr : &*found;
}

// a view's options: an object (absent: {}, every option at its default)
void check_options(const json& options) {
  if (!options.is_object()) throw BadInput("options", options.dump(), "expected an object");
}

// option `name` of a view as a number within [lower, upper]; `fallback` where absent
double number_option(const json& options, const char* name, double fallback, double lower,
                     double upper) {
  if (!options.contains(name)) return fallback;
  const json& given = options.at(name);
  if (!given.is_number())
    throw BadInput(name, given.dump(), "expected a number");
  const double value = given.get<double>();
  if (!(value >= lower && value <= upper))
    throw BadInput(name, exact(value), fmt::format("expected a number in [{}, {}]", lower, upper));
  return value;
}

double whole_option(const json& options, const char* name, double fallback, double lower,
                    double upper) {
  const double value = number_option(options, name, fallback, lower, upper);
  if (value != std::floor(value)) throw BadInput(name, exact(value), "expected a whole number");
  return value;
}

std::string text_option(const json& options, const char* name, std::size_t longest) {
  if (!options.contains(name) || !options.at(name).is_string())
    throw BadInput(name, options.contains(name) ? options.at(name).dump() : "(missing)",
                   "expected a text");
  std::string text = options.at(name).get<std::string>();
  if (text.size() > longest) throw BadInput(name, text, "too long");
  return text;
}

// one key as `--set` and Python spell it, where `scene` differs from `base`
struct Assignment {
  std::string key;
  SceneValue value;
};

std::vector<Assignment> changed_keys(const Scene& base, const Scene& scene) {
  std::vector<Assignment> changed;
  for (const KeySpec& spec : scene_schema(scene).keys) {
    const std::string key(spec.key);
    const auto now = scene.values.find(key);
    if (now == scene.values.end()) continue;
    const auto before = base.values.find(key);
    if (before == base.values.end() || before->second != now->second)
      changed.push_back({key, now->second});
  }
  return changed;
}

// a Python literal of a scene value (a number's shortest exact text, a text in quotes)
std::string python_literal(const SceneValue& value) {
  if (const auto* text = std::get_if<std::string>(&value)) return json(*text).dump();
  return exact(std::get<double>(value));
}

// the words `impactlab COMMAND SCENE --set ...` with the options after them
std::vector<std::string> command_words(const std::string& command, const std::string& scene_source,
                                       const std::vector<Assignment>& changed,
                                       const std::vector<std::string>& options) {
  std::vector<std::string> words = {"impactlab", command, scene_source};
  for (const Assignment& assignment : changed) {
    words.push_back("--set");
    words.push_back(assignment.key + "=" + to_text(assignment.value));
  }
  words.insert(words.end(), options.begin(), options.end());
  return words;
}

// `impactlab.FUNCTION("scene", option=..., key=...)`; dotted keys as **{...}
std::string python_call(const std::string& function, const std::string& scene_source,
                        const std::vector<std::pair<std::string, std::string>>& options,
                        const std::vector<Assignment>& changed) {
  std::string call = "impactlab." + function + "(" + json(scene_source).dump();
  for (const auto& [name, literal] : options) call += ", " + name + "=" + literal;
  std::string dotted;
  for (const Assignment& assignment : changed) {
    if (assignment.key.find('.') == std::string::npos) {
      call += ", " + assignment.key + "=" + python_literal(assignment.value);
    } else {
      dotted += (dotted.empty() ? "" : ", ") + json(assignment.key).dump() + ": " +
                python_literal(assignment.value);
    }
  }
  if (!dotted.empty()) call += ", **{" + dotted + "}";
  return call + ")";
}

// a stroboscopic section of `points` points after exactly `transient` periods
SectionRequest strobe_request(double transient, std::uint64_t points) {
  SectionRequest request;
  request.section = parse_section("strobe", "section");
  request.settle = false;
  request.transient_periods = transient;
  request.points = points;
  return request;
}

std::string sweep_param(const DiagramView& view) {
  return fmt::format("{}={}:{}:{}", view.key, exact(view.from), exact(view.to), view.columns);
}

// Points with t, q, qdot (section points, trajectory samples) as the page's
// columns t, q, qdot.
template <class Point>
json point_columns(const std::vector<Point>& points) {
  std::vector<double> t, q, qdot;
  for (const Point& point : points) {
    t.push_back(point.t);
    q.push_back(point.q);
    qdot.push_back(point.qdot);
  }
  return {{"t", t}, {"q", q}, {"qdot", qdot}};
}

// The impacts of a run as it goes, at most `limit` of them (a chattering run
// of thousands of periods has millions): the walls and the time series' marks.
class ImpactCollector final : public EventSink {
 public:
  explicit ImpactCollector(std::size_t limit) : limit_(limit) {}
  void write(const EventRecord& event) override {
    if (event.kind != EventKind::impact || t.size() >= limit_) return;
    t.push_back(event.t);
    q.push_back(event.q);
    wall.push_back(event.wall);
  }
  std::vector<double> t, q;
  std::vector<int> wall;

 private:
  std::size_t limit_;
};

// the numeric parameter a diagram or an orbit view varies: a number key of the scene
void check_numeric_key(const Scene& scene, const std::string& key, const char* option) {
  const KeySpec* spec = find_key(scene_schema(scene), key);
  if (spec == nullptr || spec->is_text)
    throw BadInput(option, key, "not a numeric key of the scene's oscillator " + scene.oscillator);
}

}  // namespace

json explore_scene_description(const Scene& scene) {
  const SceneSchema& schema = scene_schema(scene);
  json keys = json::array();
  for (const KeySpec& spec : schema.keys) {
    const std::string key(spec.key);
    json entry = {{"key", key}, {"unit", spec.unit}, {"help", spec.help},
                  {"text", spec.is_text}};
    const auto value = scene.values.find(key);
    if (spec.is_text) {
      entry["value"] = value != scene.values.end() ? to_text(value->second) : "";
      json choices = json::array();
      for (std::string_view choice : spec.choices) choices.push_back(choice);
      entry["choices"] = choices;
      entry["slider"] = false;
    } else {
      entry["value"] = value != scene.values.end() ? std::get<double>(value->second) : 0.0;
      entry["lower"] = bound(spec.lower);
      entry["upper"] = bound(spec.upper);
      entry["lower_open"] = spec.lower_open;
      entry["upper_open"] = spec.upper_open;
      entry["range"] = range_text(spec);
      entry["slider"] = !entry["lower"].is_null() && !entry["upper"].is_null();
    }
    keys.push_back(entry);
  }
  return {{"scene", scene.name},
          {"oscillator", scene.oscillator},
          {"main_coordinate", schema.main_coordinate},
          {"keys", keys}};
}

Scene explore_scene(const Scene& base, const json& values, const ExploreLimits& limits) {
  if (!values.is_object()) throw BadInput("values", values.dump(), "expected an object of scene keys");
  const SceneSchema& schema = scene_schema(base);
  if (values.size() > schema.keys.size())
    throw BadInput("values", fmt::format("{} keys", values.size()),
                   fmt::format("the scene has {} keys", schema.keys.size()));
  Scene scene = base;
  for (const auto& [key, given] : values.items()) {
    std::string text;
    if (given.is_number()) {
      text = exact(given.get<double>());
    } else if (given.is_string()) {
      text = given.get<std::string>();
      if (text.size() > limits.max_value_chars) throw BadInput(key, text, "too long");
    } else {
      throw BadInput(key, given.dump(), "expected a number or a text");
    }
    // a key left as the base scene has it is not assigned (a sweep's
    // classification tolerance yields only to keys the user set)
    const auto before = base.values.find(key);
    if (before != base.values.end() && to_text(before->second) == text) continue;
    apply_override(scene, key + "=" + text);
  }
  return scene;
}

TrajectoryView trajectory_view(const json& options, const ExploreLimits& limits) {
  check_options(options);
  TrajectoryView view;
  view.periods = number_option(options, "periods", view.periods, 1e-3, limits.max_periods);
  view.samples_per_period = static_cast<int>(
      whole_option(options, "samples_per_period", view.samples_per_period, 1, 4096));
  if (view.periods * view.samples_per_period > limits.max_samples)
    throw BadInput("periods", exact(view.periods),
                   fmt::format("periods × samples_per_period is over {} samples", limits.max_samples));
  return view;
}

SectionView section_view(const json& options, const ExploreLimits& limits) {
  check_options(options);
  SectionView view;
  view.transient = number_option(options, "transient", view.transient, 0, limits.max_periods);
  view.points = static_cast<std::uint64_t>(whole_option(
      options, "points", static_cast<double>(view.points), 1,
      static_cast<double>(limits.max_section_points)));
  return view;
}

DiagramView diagram_view(const json& options, const Scene& scene, const ExploreLimits& limits) {
  check_options(options);
  DiagramView view;
  view.key = text_option(options, "key", 100);
  check_numeric_key(scene, view.key, "key");
  view.from = number_option(options, "from", 0.0, -1e300, 1e300);
  view.to = number_option(options, "to", 0.0, -1e300, 1e300);
  view.columns = static_cast<int>(whole_option(options, "columns", view.columns, 2, limits.max_columns));
  view.transient = number_option(options, "transient", view.transient, 0, limits.max_periods);
  view.points = static_cast<std::uint64_t>(whole_option(
      options, "points", static_cast<double>(view.points), 1,
      static_cast<double>(limits.max_column_points)));
  view.threads = static_cast<int>(whole_option(options, "threads", view.threads, 1, limits.max_threads));
  // the sweep's own checks: each value admissible for the key
  SweepSpec spec;
  spec.params = {sweep_param(view)};
  spec.section = strobe_request(view.transient, view.points);
  make_sweep_plan(spec, scene, scene_schema(scene));
  return view;
}

OrbitView orbit_view(const json& options, const Scene& scene, const ExploreLimits& limits) {
  check_options(options);
  OrbitView view;
  if (options.contains("key")) {
    view.key = text_option(options, "key", 100);
    check_numeric_key(scene, view.key, "key");
    view.value = number_option(options, "value", 0.0, -1e300, 1e300);
    view.t = number_option(options, "t", 0.0, -1e300, 1e300);
    view.q = number_option(options, "q", 0.0, -1e300, 1e300);
    view.qdot = number_option(options, "qdot", 0.0, -1e300, 1e300);
  }
  view.transient = number_option(options, "transient", view.transient, 0, limits.max_periods);
  view.lyapunov_points = static_cast<std::uint64_t>(whole_option(
      options, "lyapunov_points", static_cast<double>(view.lyapunov_points), 1,
      static_cast<double>(limits.max_section_points)));
  orbit_scene(scene, view);  // the scene's own checks of the values
  return view;
}

Scene orbit_scene(const Scene& scene, const OrbitView& view) {
  Scene at = scene;
  if (view.key.empty()) return at;
  apply_override(at, view.key + "=" + exact(view.value));
  const SceneSchema& schema = scene_schema(scene);
  const std::string main(schema.main_coordinate);
  const std::string position = "initial." + main, rate = "initial." + main + "_dot";
  if (find_key(schema, position) != nullptr && find_key(schema, rate) != nullptr) {
    apply_override(at, "t0=" + exact(view.t));
    apply_override(at, position + "=" + exact(view.q));
    apply_override(at, rate + "=" + exact(view.qdot));
  }
  return at;
}

json run_trajectory(const Scene& scene, const TrajectoryView& view, const ExploreProgress& report) {
  RunRequest request;
  request.periods = view.periods;
  request.sample_step = scene.forcing_period() / view.samples_per_period;
  // the impacts alone are kept, as many as the samples at most
  ImpactCollector impacts(static_cast<std::size_t>(view.periods * view.samples_per_period) + 1);
  request.keep_events = false;
  request.event_sink = &impacts;
  request.progress = report.progress;
  const RunOutput output = simulate(scene, request);
  // the walls where the run's impacts show them: one line per wall whose
  // impacts all happen at one q (a fixed wall)
  std::map<int, std::pair<double, double>> wall_span;
  for (std::size_t k = 0; k < impacts.t.size(); ++k) {
    const double at = impacts.q[k];
    const auto span = wall_span.try_emplace(impacts.wall[k], at, at).first;
    span->second.first = std::min(span->second.first, at);
    span->second.second = std::max(span->second.second, at);
  }
  json walls = json::array();
  for (const auto& [wall, span] : wall_span)
    if (span.second - span.first <= 1e-9 * (1.0 + std::abs(span.first)))
      walls.push_back({{"wall", wall}, {"q", span.first}});
  json out = point_columns(output.samples);
  out["sample_step"] = request.sample_step;
  out["impacts"] = {{"t", impacts.t}, {"q", impacts.q}, {"wall", impacts.wall}};
  out["impact_count"] = output.impacts;
  out["walls"] = walls;
  out["termination"] = to_string(output.termination);
  out["steps"] = output.steps;
  return out;
}

json run_section(const Scene& scene, const SectionView& view, const ExploreProgress& report) {
  // a strobe counts in forcing periods: a scene without omega is refused here
  static_cast<void>(scene.forcing_period());
  SectionRequest request = strobe_request(view.transient, view.points);
  // a report per forcing period (per point of the record): a superseded run ends at the next
  request.progress = report.progress;
  const SectionResult result = poincare(scene, request);
  json out = point_columns(result.points);
  out["termination"] = to_string(result.termination);
  out["transient_end"] = to_string(result.transient_end);
  return out;
}

json run_diagram(const Scene& scene, const DiagramView& view, const ExploreProgress& report) {
  SweepSpec spec;
  spec.params = {sweep_param(view)};
  spec.section = strobe_request(view.transient, view.points);
  const SweepTarget target = sweep_target(scene);
  const SweepPlan plan = make_sweep_plan(spec, scene, *target.schema);
  const std::vector<SweepTask> tasks = sweep_tasks(plan);
  std::vector<const SweepTask*> all;
  for (const SweepTask& task : tasks) all.push_back(&task);
  SweepJobOptions job;
  job.threads = view.threads;
  job.keep_points = false;
  job.progress = report.progress;
  // each finished value as one column, handed on as it comes (under the job's lock)
  job.on_record = [&](const SweepRecord& record) {
    SweepTable rows;
    add_bifurcation_rows(rows, plan, record);
    json column = {{"index", record.index[0]},
                   {"value", plan.axes[0].value(record.index[0])},
                   {"t", rows.point_t},
                   {"q", rows.point_q},
                   {"qdot", rows.point_qdot},
                   {"period", record.classification.period},
                   {"termination", to_string(record.result.termination)}};
    if (report.add_column) report.add_column(column);
  };
  run_sweep(scene, target, plan, all, job);
  return {{"key", view.key}, {"from", view.from}, {"to", view.to}, {"columns", view.columns}};
}

json run_orbit(const Scene& scene, const OrbitView& view, const ExploreProgress& report) {
  const Scene at = orbit_scene(scene, view);
  auto checkpoint = [&](double fraction) {
    if (report.progress) report.progress(fraction);
  };
  PeriodicJob job;
  job.transient = view.transient;
  const PeriodicJobResult found = find_periodic_orbit(at, job);
  checkpoint(0.4);
  json out = {{"periodic", periodic_record(at, found)}};
  // the orbit over its period, run from its point on the section: each
  // component of the state that the scene has an initial key for (a
  // tally such as the friction work has none and feeds nothing back)
  const PeriodicResult& orbit = found.result;
  const SceneSchema& schema = scene_schema(at);
  const std::string main(schema.main_coordinate);
  Scene start = at;
  int coordinates_set = 0;
  if (orbit.converged && orbit.state.size() == orbit.state_names.size()) {
    apply_override(start, "t0=" + exact(orbit.t_section));
    for (std::size_t i = 0; i < orbit.state.size(); ++i) {
      const std::string key = "initial." + orbit.state_names[i];
      if (find_key(schema, key) == nullptr) continue;
      apply_override(start, key + "=" + exact(orbit.state[i]));
      coordinates_set += orbit.state_names[i] == main || orbit.state_names[i] == main + "_dot";
    }
  }
  if (coordinates_set == 2) {
    RunRequest request;
    request.periods = found.request.period;
    request.sample_step = at.forcing_period() / 256.0;
    request.keep_events = false;
    out["orbit"] = point_columns(simulate(start, request).samples);
  }
  checkpoint(0.6);
  SectionRequest lyapunov = strobe_request(view.transient, view.lyapunov_points);
  lyapunov.lyapunov = true;
  const SectionResult exponent = poincare(at, lyapunov);
  out["lyapunov"] = std::isfinite(exponent.lyapunov) ? json(exponent.lyapunov) : json(nullptr);
  out["lyapunov_text"] = exact(exponent.lyapunov);
  out["lyapunov_note"] = exponent.lyapunov_note;
  checkpoint(1.0);
  return out;
}

ExploreExport explore_export(const std::string& view_kind, const json& options,
                             const std::string& scene_source, const Scene& base,
                             const Scene& scene, const ExploreLimits& limits) {
  ExploreExport out;
  const std::vector<Assignment> changed = changed_keys(base, scene);
  if (view_kind == "trajectory") {
    const TrajectoryView view = trajectory_view(options, limits);
    const std::string sample = exact(scene.forcing_period() / view.samples_per_period);
    out.commands.push_back(command_words(
        "simulate", scene_source, changed, {"--periods", exact(view.periods), "--sample", sample}));
    out.python_calls.push_back(python_call(
        "simulate", scene_source, {{"periods", exact(view.periods)}, {"sample", sample}}, changed));
  } else if (view_kind == "section") {
    const SectionView view = section_view(options, limits);
    const std::string points = std::to_string(view.points);
    out.commands.push_back(command_words("poincare", scene_source, changed,
                                         {"--transient", exact(view.transient), "--points", points}));
    out.python_calls.push_back(python_call(
        "poincare", scene_source, {{"transient", exact(view.transient)}, {"points", points}},
        changed));
  } else if (view_kind == "diagram") {
    const DiagramView view = diagram_view(options, scene, limits);
    const std::string points = std::to_string(view.points), threads = std::to_string(view.threads);
    out.commands.push_back(command_words(
        "sweep", scene_source, changed,
        {"--param", sweep_param(view), "--transient", exact(view.transient), "--points", points,
         "--threads", threads}));
    out.python_calls.push_back(python_call(
        "sweep", scene_source,
        {{"param", json(sweep_param(view)).dump()}, {"transient", exact(view.transient)},
         {"points", points}, {"threads", threads}},
        changed));
  } else if (view_kind == "orbit") {
    const OrbitView view = orbit_view(options, scene, limits);
    const Scene at = orbit_scene(scene, view);
    const std::vector<Assignment> orbit_changed = changed_keys(base, at);
    const std::string points = std::to_string(view.lyapunov_points);
    out.commands.push_back(command_words("periodic", scene_source, orbit_changed,
                                         {"--transient", exact(view.transient)}));
    out.commands.push_back(command_words(
        "poincare", scene_source, orbit_changed,
        {"--lyapunov", "--transient", exact(view.transient), "--points", points}));
    out.python_calls.push_back(python_call(
        "periodic", scene_source, {{"transient", exact(view.transient)}}, orbit_changed));
    out.python_calls.push_back(python_call(
        "poincare", scene_source,
        {{"lyapunov", "True"}, {"transient", exact(view.transient)}, {"points", points}},
        orbit_changed));
    out.scene_toml = scene_file_text(at, scene_schema(at));
    return out;
  } else {
    throw BadInput("view", view_kind, "expected trajectory, section, diagram or orbit");
  }
  out.scene_toml = scene_file_text(scene, scene_schema(scene));
  return out;
}

std::string shell_command(const std::vector<std::string>& words) {
  std::string line;
  for (const std::string& word : words) {
    if (!line.empty()) line += ' ';
    const bool plain = !word.empty() && std::all_of(word.begin(), word.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("_./:=+-,@%").find(c) != std::string_view::npos;
    });
    if (plain) {
      line += word;
    } else {
      line += '\'';
      for (char c : word) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
      line += '\'';
    }
  }
  return line;
}

}  // namespace impactlab
