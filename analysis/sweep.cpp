#include <impactlab/analysis/sweep.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

double parse_finite(const std::string& text, bool& ok) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  ok = end != text.c_str() && *end == '\0' && std::isfinite(value);
  return value;
}

// doubles that may be NaN or ±∞ travel as text ("nan", "-inf")
double number_from_text(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

}  // namespace

double SweepAxis::value(int index) const {
  if (count <= 1) return from;
  if (index == count - 1) return to;
  return from + (to - from) * static_cast<double>(index) / static_cast<double>(count - 1);
}

SweepAxis parse_axis(std::string_view text, std::string_view option) {
  const auto bad = [&](const std::string& why) {
    return BadInput(std::string(option), std::string(text), why);
  };
  const auto equals = text.find('=');
  if (equals == std::string_view::npos || equals == 0) throw bad("expected NAME=FROM:TO:N");
  SweepAxis axis;
  axis.name = std::string(text.substr(0, equals));
  const std::string range(text.substr(equals + 1));
  const auto first = range.find(':');
  const auto second = first == std::string::npos ? first : range.find(':', first + 1);
  if (second == std::string::npos || range.find(':', second + 1) != std::string::npos)
    throw bad("expected NAME=FROM:TO:N");
  bool ok_from = false, ok_to = false, ok_count = false;
  axis.from = parse_finite(range.substr(0, first), ok_from);
  axis.to = parse_finite(range.substr(first + 1, second - first - 1), ok_to);
  const double count = parse_finite(range.substr(second + 1), ok_count);
  if (!ok_from || !ok_to) throw bad("FROM and TO must be finite numbers");
  if (!ok_count || count < 1.0 || count > 1e7 || count != std::floor(count))
    throw bad("N must be a whole number from 1 to 10^7");
  axis.count = static_cast<int>(count);
  return axis;
}

SweepDirection parse_direction(std::string_view text, std::string_view option) {
  if (text == "up") return SweepDirection::up;
  if (text == "down") return SweepDirection::down;
  if (text == "both") return SweepDirection::both;
  throw BadInput(std::string(option), std::string(text), "expected up, down or both");
}

std::string_view to_string(SweepDirection direction) {
  switch (direction) {
    case SweepDirection::up: return "up";
    case SweepDirection::down: return "down";
    case SweepDirection::both: return "both";
  }
  return "up";
}

Scene scene_at(const Scene& base, const SceneSchema& schema, const SweepPlan& plan,
               const std::array<int, 2>& index) {
  Scene scene = base;
  if (plan.samples > 0) {
    // the value, and this sample's initial state from the box
    scene.values[plan.axes[0].name] = plan.axes[0].value(index[0]);
    for (std::size_t k = 0; k < plan.box.size(); ++k)
      scene.values[plan.box[k].key] =
          box_value(plan.box[k], plan.seed, index[0], index[1], static_cast<int>(k));
  } else {
    for (std::size_t a = 0; a < plan.axes.size(); ++a)
      scene.values[plan.axes[a].name] = plan.axes[a].value(index[a]);
  }
  validate(scene, schema);
  return scene;
}

void validate_plan(const SweepPlan& plan, const Scene& scene, const SceneSchema& schema) {
  if (plan.axes.empty() || plan.axes.size() > 2)
    throw BadInput("param", std::to_string(plan.axes.size()), "give one or two `param`");
  if (plan.axes.size() == 2 && plan.axes[0].name == plan.axes[1].name)
    throw BadInput("param", plan.axes[1].name, "the two swept parameters must differ");
  for (const auto& axis : plan.axes) {
    const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                   [&](const KeySpec& k) { return k.key == axis.name; });
    if (spec == schema.keys.end() || spec->is_text)
      throw BadInput("param", axis.name,
                     fmt::format("not a numeric key of oscillator {}", schema.oscillator));
    // the ends of the range are admissible (BadInput names the key and value otherwise)
    Scene probe = scene;
    for (double value : {axis.from, axis.to}) {
      probe.values[axis.name] = value;
      validate(probe, schema);
    }
  }
  if (plan.chunks < 1) throw BadInput("chunks", std::to_string(plan.chunks), "must be >= 1");
}

std::vector<SweepTask> sweep_tasks(const SweepPlan& plan) {
  std::vector<SweepTask> tasks;
  if (plan.samples > 0) {
    // the samples of each value in tasks of at most samples_per_task, value
    // by value, in sample order: threads and ranks share even one value
    for (int i = 0; i < plan.axes[0].count; ++i)
      for (int first = 0; first < plan.samples; first += samples_per_task) {
        SweepTask task;
        task.id = static_cast<int>(tasks.size());
        for (int s = first; s < std::min(plan.samples, first + samples_per_task); ++s)
          task.points.push_back({i, s});
        tasks.push_back(std::move(task));
      }
    return tasks;
  }
  if (plan.axes.size() == 1) {
    const int n = plan.axes[0].count;
    const int chunks = std::min(plan.chunks, n);
    std::vector<int> directions;
    if (plan.direction != SweepDirection::down) directions.push_back(1);
    if (plan.direction != SweepDirection::up) directions.push_back(-1);
    // up follows the parameter's increasing values, whichever way the range
    // is written
    const bool ascending = plan.axes[0].ascending();
    for (int direction : directions)
      for (int c = 0; c < chunks; ++c) {
        SweepTask task;
        task.id = static_cast<int>(tasks.size());
        task.direction = direction;
        const int begin = static_cast<int>(static_cast<long>(n) * c / chunks);
        const int end = static_cast<int>(static_cast<long>(n) * (c + 1) / chunks);
        for (int k = 0; k < end - begin; ++k)
          task.points.push_back({(direction > 0) == ascending ? begin + k : end - 1 - k, 0});
        tasks.push_back(std::move(task));
      }
    return tasks;
  }
  for (int j = 0; j < plan.axes[1].count; ++j) {
    SweepTask task;
    task.id = j;
    for (int i = 0; i < plan.axes[0].count; ++i) task.points.push_back({i, j});
    tasks.push_back(std::move(task));
  }
  return tasks;
}

namespace {

// the share of the record window's impacts that stuck; NaN without impacts
double stick_fraction_of(const SectionResult& result) {
  return result.impacts > 0
             ? static_cast<double>(result.stick_impacts) / static_cast<double>(result.impacts)
             : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

Classification classify(const SectionResult& result, const SweepPlan& plan) {
  Classification classification;
  if (result.periods_recorded > 0.0)
    classification.impacts_per_period =
        static_cast<double>(result.impacts) / result.periods_recorded;
  classification.contact = result.contact_phases > 0 || result.rests_in_contact;
  classification.stick_fraction = stick_fraction_of(result);
  const auto& points = result.points;
  const std::size_t n = points.size();
  double scale = 1.0;
  for (const auto& p : points) scale = std::max(scale, 1.0 + std::hypot(p.q, p.qdot));
  for (int p = 1; p <= plan.max_period && static_cast<std::size_t>(2 * p) <= n; ++p) {
    bool repeats = true;
    for (std::size_t k = 0; k + p < n && repeats; ++k)
      repeats = std::hypot(points[k + p].q - points[k].q, points[k + p].qdot - points[k].qdot) <=
                plan.period_tolerance * scale;
    if (repeats) {
      classification.period = p;
      break;
    }
  }
  return classification;
}

std::string to_json_line(const SweepRecord& record) {
  const SectionResult& r = record.result;
  nlohmann::json t = nlohmann::json::array(), q = nlohmann::json::array(),
                 qdot = nlohmann::json::array(), wall = nlohmann::json::array();
  for (const auto& p : r.points) {
    t.push_back(p.t);
    q.push_back(p.q);
    qdot.push_back(p.qdot);
    wall.push_back(p.wall);
  }
  nlohmann::json line = {
      {"task", record.task},
      {"position", record.position},
      {"index", record.index},
      {"direction", record.direction},
      {"termination", to_string(r.termination)},
      {"omega", r.omega},
      {"forcing_period", r.forcing_period},
      {"record_start", r.record_start},
      {"transient_periods", r.transient_periods},
      {"transient_end", to_string(r.transient_end)},
      {"periods_recorded", r.periods_recorded},
      {"impacts", r.impacts},
      {"contact_phases", r.contact_phases},
      {"rests_in_contact", r.rests_in_contact},
      {"stick_impacts", r.stick_impacts},
      {"min_impact_speed", fmt::format("{}", r.min_impact_speed)},
      {"steps", r.steps},
      {"rhs_evaluations", r.rhs_evaluations},
      {"lyapunov", fmt::format("{}", r.lyapunov)},
      {"lyapunov_note", r.lyapunov_note},
      {"t", t},
      {"q", q},
      {"qdot", qdot},
      {"wall", wall},
      {"point_count", std::max<std::uint64_t>(r.point_count, r.points.size())},
      {"period", record.classification.period},
      {"impacts_per_period", record.classification.impacts_per_period},
      {"contact", record.classification.contact},
  };
  if (!r.lyapunov_spectrum.empty()) {
    // as text, so that -inf and nan survive JSON
    nlohmann::json exponents = nlohmann::json::array(), errors = nlohmann::json::array();
    for (std::size_t i = 0; i < r.lyapunov_spectrum.size(); ++i) {
      exponents.push_back(fmt::format("{}", r.lyapunov_spectrum[i]));
      errors.push_back(fmt::format("{}", r.lyapunov_spectrum_error[i]));
    }
    line["lyapunov_spectrum"] = exponents;
    line["lyapunov_spectrum_error"] = errors;
    line["lyapunov_spectrum_note"] = r.lyapunov_spectrum_note;
  }
  if (r.final_state) {
    line["final_state"] = r.final_state->state;
    line["final_mode"] = r.final_state->mode;
  }
  return line.dump();
}

std::optional<SweepRecord> from_json_line(std::string_view text) {
  try {
    const nlohmann::json line = nlohmann::json::parse(text);
    SweepRecord record;
    record.task = line.at("task");
    record.position = line.at("position");
    record.index = line.at("index");
    record.direction = line.at("direction");
    SectionResult& r = record.result;
    const auto termination = parse_section_termination(line.at("termination").get<std::string>());
    if (!termination) return std::nullopt;
    r.termination = *termination;
    r.omega = line.at("omega");
    r.forcing_period = line.at("forcing_period");
    r.record_start = line.at("record_start");
    r.transient_periods = line.at("transient_periods");
    const auto transient_end = parse_transient_end(line.at("transient_end").get<std::string>());
    if (!transient_end) return std::nullopt;
    r.transient_end = *transient_end;
    r.periods_recorded = line.at("periods_recorded");
    r.impacts = line.at("impacts");
    r.contact_phases = line.at("contact_phases");
    r.rests_in_contact = line.at("rests_in_contact");
    r.stick_impacts = line.at("stick_impacts");
    // a line written before the impact speed was kept has none
    r.min_impact_speed = number_from_text(line.value("min_impact_speed", std::string("nan")));
    r.steps = line.at("steps");
    r.rhs_evaluations = line.at("rhs_evaluations");
    r.lyapunov = number_from_text(line.at("lyapunov"));
    r.lyapunov_note = line.at("lyapunov_note");
    if (line.contains("lyapunov_spectrum")) {
      for (const auto& text : line.at("lyapunov_spectrum"))
        r.lyapunov_spectrum.push_back(number_from_text(text));
      for (const auto& text : line.at("lyapunov_spectrum_error"))
        r.lyapunov_spectrum_error.push_back(number_from_text(text));
      r.lyapunov_spectrum_note = line.at("lyapunov_spectrum_note");
    }
    const auto& t = line.at("t");
    for (std::size_t k = 0; k < t.size(); ++k)
      r.points.push_back({t[k], line.at("q")[k], line.at("qdot")[k], line.at("wall")[k]});
    // a record written without its points (drop_points) keeps their count
    r.point_count = line.value("point_count", static_cast<std::uint64_t>(r.points.size()));
    if (line.contains("final_state"))
      r.final_state = ContinuationState{line.at("final_state"), line.at("final_mode")};
    record.classification.period = line.at("period");
    record.classification.impacts_per_period = line.at("impacts_per_period");
    record.classification.contact = line.at("contact");
    record.classification.stick_fraction = stick_fraction_of(r);
    return record;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

std::vector<SweepRecord> run_sweep_task(
    const Scene& base, const SweepTarget& target, const SweepPlan& plan, const SweepTask& task,
    const std::function<const SweepRecord*(int position)>& done,
    const std::function<void(const SweepRecord&)>& on_record,
    const std::function<bool()>& keep_going, bool keep_points, SeriesLane* series_lane) {
  std::vector<SweepRecord> records;
  std::optional<ContinuationState> previous;
  for (std::size_t position = 0; position < task.points.size(); ++position) {
    const int pos = static_cast<int>(position);
    if (const SweepRecord* finished = done(pos)) {
      records.push_back(*finished);
      if (!keep_points) drop_points(records.back());
      previous = finished->result.final_state;
      continue;
    }
    if (!keep_going()) break;
    const Scene scene = scene_at(base, *target.schema, plan, task.points[position]);
    SectionRequest request = plan.section;
    request.integrator = plan.classification_integrator;
    request.series_lane = series_lane;
    if (plan.follow_attractor) request.start = previous;
    SweepRecord record;
    record.task = task.id;
    record.position = pos;
    record.index = task.points[position];
    record.direction = task.direction;
    record.result = target.section(scene, request);
    record.classification = classify(record.result, plan);
    previous = record.result.final_state;
    on_record(record);
    if (!keep_points) drop_points(record);
    records.push_back(std::move(record));
  }
  return records;
}

void drop_points(SweepRecord& record) {
  record.result.point_count =
      std::max<std::uint64_t>(record.result.point_count, record.result.points.size());
  // a swap, not `= {}`: assigning an empty list keeps the capacity
  std::vector<SectionPoint>().swap(record.result.points);
}

}  // namespace impactlab
