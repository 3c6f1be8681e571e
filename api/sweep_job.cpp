#include <impactlab/api/sweep_job.hpp>

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <string>

#include <fmt/format.h>
#include <omp.h>

#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/scene_record.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/simulate/series_batch.hpp>

namespace impactlab {

namespace {

// The integrator a sweep classifies at where it is not the scene's own
// (plan.classification_integrator) and why (plan.classification_note): the
// scene's integrator.classification_* (chosen from data, docs/performance.md)
// for a sweep whose files hold classes only, unless turned off, not stated by
// the scene, or overruled by an integrator key the user set or swept.
void choose_classification_integrator(SweepPlan& plan, const SweepSpec& spec,
                                      const Scene& scene) {
  if (spec.classification_tolerance != "auto" && spec.classification_tolerance != "off")
    throw BadInput("classification_tol", spec.classification_tolerance,
                   "expected auto or off");
  const auto note = [&](const std::string& why) {
    plan.classification_note = "the scene's integrator: " + why;
  };
  if (spec.classification_tolerance == "off") return note("classification tolerance turned off");
  if (plan.axes.size() != 2)
    return note("a 1D sweep writes section points (bifurcation.csv)");
  for (const std::string key : {"integrator.method", "integrator.rtol", "integrator.atol"})
    if (scene.assigned.contains(key)) return note(key + " set by the user");
  for (const SweepAxis& axis : plan.axes)
    if (axis.name.starts_with("integrator.")) return note(axis.name + " swept");
  const double rtol = scene.number("integrator.classification_rtol");
  const double atol = scene.number("integrator.classification_atol");
  if (!(rtol > 0.0) || !(atol > 0.0))
    return note("the scene states no classification tolerance");
  const std::string& method = scene.text("integrator.classification_method");
  plan.classification_integrator =
      IntegratorSetting{method == "same" ? scene.text("integrator.method") : method, rtol, atol};
  plan.classification_note =
      "classification only (2D map): the scene's integrator.classification_method, "
      "classification_rtol and classification_atol";
}

// Refuses, before any point runs or any task is laid out, a sweep whose rows
// pass the scene's limits.max_rows: a 2D map writes one row per grid point
// (classes.csv, basins.csv), a 1D sweep one summary row per value and
// direction and up to `points` section points each (bifurcation.csv, which
// Python holds in memory). BadInput names the grid's option (`param`, `x/y`)
// or `points` where the grid alone fits and the points per value do not.
void check_sweep_size(const SweepPlan& plan, const SweepSpec& spec, const Scene& scene) {
  const double row_budget = scene.number("limits.max_rows");
  double grid_points = 1.0;
  std::string grid_text;  // the axes as given
  for (const SweepAxis& axis : plan.axes) {
    grid_points *= static_cast<double>(axis.count);
    grid_text += (grid_text.empty() ? "" : " ") + axis.name + "=" +
                 fmt::format("{}:{}:{}", axis.from, axis.to, axis.count);
  }
  const bool one_dimensional = plan.axes.size() == 1;
  const double directions = one_dimensional && plan.direction == SweepDirection::both ? 2.0 : 1.0;
  const double grid_rows = grid_points * directions;
  const double point_rows =
      one_dimensional ? grid_rows * static_cast<double>(spec.section.points) : grid_rows;
  const std::string over = fmt::format(
      "over limits.max_rows = {} (raise it with `set` limits.max_rows=N)",
      static_cast<std::uint64_t>(row_budget));
  if (grid_rows > row_budget)
    throw BadInput(spec.param_key, grid_text,
                   fmt::format("the grid would write {:.3g} rows, {}", grid_rows, over));
  if (point_rows > row_budget)
    throw BadInput("points", std::to_string(spec.section.points),
                   fmt::format("{:.3g} values x {} points would write {:.3g} rows, {}", grid_rows,
                               spec.section.points, point_rows, over));
}

nlohmann::json integrator_record(const IntegratorSetting& integrator) {
  return {{"method", integrator.method}, {"rtol", integrator.rtol}, {"atol", integrator.atol}};
}

}  // namespace

SweepPlan make_sweep_plan(const SweepSpec& spec, const Scene& scene, const SceneSchema& schema) {
  SweepPlan plan;
  for (const auto& text : spec.params) plan.axes.push_back(parse_axis(text, spec.param_key));
  if (plan.axes.empty() || plan.axes.size() > 2)
    throw BadInput(spec.param_key, std::to_string(plan.axes.size()) + " axes",
                   "give one (bifurcation sweep) or two (classification map)");
  plan.direction = parse_direction(spec.direction, "direction");
  plan.chunks = spec.chunks;
  plan.section = spec.section;
  plan.period_tolerance = spec.period_tolerance;
  plan.max_period = spec.max_period;
  // the settling transient tells repeats at a tenth of the period test's
  // tolerance, so that a settled point's record passes that test
  plan.section.settle_tolerance = spec.period_tolerance / 10.0;
  plan.section.settle_max_period = spec.max_period;
  // Lyapunov: on by default for 2D maps, off for 1D sweeps
  plan.section.lyapunov = spec.lyapunov.value_or(plan.axes.size() == 2);
  check_sweep_size(plan, spec, scene);
  validate_plan(plan, scene, schema);
  // a key the scene's model does not read would sweep nothing
  for (const SweepAxis& axis : plan.axes)
    refuse_unread_key(scene, schema, axis.name, spec.param_key);
  if (plan.axes.size() == 2 && plan.direction != SweepDirection::up)
    throw BadInput("direction", spec.direction,
                   "a 2D sweep follows the first parameter upwards only");
  choose_classification_integrator(plan, spec, scene);
  return plan;
}

nlohmann::json sweep_definition(const SweepPlan& plan, const Scene& scene,
                                const SceneSchema& schema, const nlohmann::json& section_record) {
  nlohmann::json axes = nlohmann::json::array();
  for (const auto& a : plan.axes) {
    const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                   [&](const KeySpec& k) { return k.key == a.name; });
    axes.push_back({{"name", a.name},
                    {"unit", std::string(spec->unit)},
                    {"from", a.from},
                    {"to", a.to},
                    {"count", a.count}});
  }
  const IntegratorSetting own = scene_integrator(scene);
  nlohmann::json definition = {
      {"scene", scene_record(scene)},
      // the integrators actually used: the transient and record that classify
      // each point, and the Lyapunov exponent's variational run (null: none)
      {"classification_integrator",
       integrator_record(plan.classification_integrator.value_or(own))},
      {"classification_integrator_note", plan.classification_note},
      {"lyapunov_integrator",
       plan.section.lyapunov || plan.section.lyapunov_spectrum ? integrator_record(own)
                                                               : nlohmann::json(nullptr)},
      {"axes", axes},
      {"direction", to_string(plan.direction)},
      {"chunks", plan.chunks},
      {"section", section_record},
      {"lyapunov", plan.section.lyapunov},
      {"lyapunov_alignment_periods", plan.section.lyapunov_alignment_periods},
      {"period_tolerance", plan.period_tolerance},
      {"max_period", plan.max_period},
      {"impactlab_version", IMPACTLAB_VERSION},
  };
  // only where asked for, so that a checkpoint written before the spectrum
  // existed still resumes
  if (plan.section.lyapunov_spectrum) definition["lyapunov_spectrum"] = true;
  return definition;
}

int sweep_batch_width(const Scene& scene, const SweepPlan& plan, const std::string& batch) {
  if (batch != "on" && batch != "off") throw BadInput("batch", batch, "expected on or off");
  const std::string own = flow_setup(scene).method;
  const bool taylor = own == "taylor" || (plan.classification_integrator &&
                                          plan.classification_integrator->method == "taylor");
  return batch == "on" && taylor ? default_batch_width : 1;
}

SweepOutput run_sweep(const Scene& scene, const SweepTarget& target, const SweepPlan& plan,
                      const std::vector<const SweepTask*>& tasks, const SweepJobOptions& options) {
  std::size_t points = 0;
  for (const SweepTask* task : tasks) points += task->points.size();
  std::mutex mutex;  // guards on_record, progress and `failure`
  std::size_t finished = 0;
  std::atomic<long> new_points{0};
  std::atomic<bool> stopped{false};
  std::exception_ptr failure;
  SweepOutput output;
  output.records.resize(tasks.size());
  output.batch_width = sweep_batch_width(scene, plan, options.batch);
  // called under the lock
  auto advance_progress = [&] {
    ++finished;
    if (options.progress)
      options.progress(static_cast<double>(finished) / static_cast<double>(points));
  };
  // task m, in a batch's lane or alone (nullptr)
  auto run_task = [&](std::size_t m, SeriesLane* lane) {
    try {
      const SweepTask& task = *tasks[m];
      output.records[m] = run_sweep_task(
          scene, target, plan, task,
          [&](int position) -> const SweepRecord* {
            if (!options.done) return nullptr;
            const auto it = options.done->find({task.id, position});
            if (it == options.done->end()) return nullptr;
            std::lock_guard lock(mutex);
            advance_progress();
            return &it->second;
          },
          [&](const SweepRecord& record) {
            std::lock_guard lock(mutex);
            if (options.on_record) options.on_record(record);
            advance_progress();
          },
          [&] {
            if (stopped) return false;
            if (options.stop_after > 0 && new_points.fetch_add(1) >= options.stop_after) {
              stopped = true;
              return false;
            }
            return true;
          },
          options.keep_points, lane);
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
      stopped = true;
    }
  };

  if (output.batch_width > 1) {
    // each thread's lanes take the next task as they finish one
    std::atomic<std::size_t> next_task{0};
#pragma omp parallel num_threads(options.threads)
    {
      try {
        run_in_lanes(output.batch_width, [&](SeriesLane& lane) {
          const std::size_t m = next_task.fetch_add(1);
          if (m >= tasks.size()) return false;
          run_task(m, &lane);
          return true;
        });
      } catch (...) {
        std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        stopped = true;
      }
    }
  } else {
#pragma omp parallel for schedule(dynamic, 1) num_threads(options.threads)
    for (std::size_t m = 0; m < tasks.size(); ++m) run_task(m, nullptr);
  }
  if (failure) std::rethrow_exception(failure);
  output.stopped = stopped;
  return output;
}

namespace {

void add_summary(SweepTable& table, const SweepRecord& r) {
  table.period.push_back(r.classification.period);
  table.impacts_per_period.push_back(r.classification.impacts_per_period);
  table.contact.push_back(r.classification.contact ? 1 : 0);
  table.stick_fraction.push_back(r.classification.stick_fraction);
  table.lyapunov.push_back(r.result.lyapunov);
  table.termination.push_back(r.result.termination);
  table.transient_periods.push_back(r.result.transient_periods);
  table.transient_end.push_back(r.result.transient_end);
  table.points.push_back(static_cast<int>(
      std::max<std::uint64_t>(r.result.point_count, r.result.points.size())));
}

}  // namespace

std::vector<SweepRecordKey> sweep_row_order(const SweepPlan& plan,
                                            const std::vector<SweepTask>& tasks) {
  std::vector<SweepRecordKey> order;
  if (plan.axes.size() == 1) {
    for (int direction : {1, -1}) {
      // this direction's records by grid index
      std::map<int, SweepRecordKey> by_index;
      for (const auto& task : tasks)
        if (task.direction == direction)
          for (std::size_t p = 0; p < task.points.size(); ++p)
            by_index[task.points[p][0]] = {task.id, static_cast<int>(p)};
      // up: increasing parameter values, whichever way the range is written
      if ((direction > 0) == plan.axes[0].ascending())
        for (const auto& [index, key] : by_index) order.push_back(key);
      else
        for (auto it = by_index.rbegin(); it != by_index.rend(); ++it) order.push_back(it->second);
    }
    return order;
  }
  for (const auto& task : tasks)
    for (std::size_t p = 0; p < task.points.size(); ++p)
      order.push_back({task.id, static_cast<int>(p)});
  return order;
}

void add_bifurcation_rows(SweepTable& table, const SweepPlan& plan, const SweepRecord& record) {
  const double value = plan.axes[0].value(record.index[0]);
  for (std::size_t k = 0; k < record.result.points.size(); ++k) {
    const SectionPoint& p = record.result.points[k];
    table.point_value.push_back(value);
    table.point_k.push_back(static_cast<int>(k));
    table.point_t.push_back(p.t);
    table.point_q.push_back(p.q);
    table.point_qdot.push_back(p.qdot);
    table.point_wall.push_back(p.wall);
    table.point_direction.push_back(record.direction);
  }
}

std::size_t lyapunov_dimension(const SweepPlan& plan,
                               const std::map<SweepRecordKey, SweepRecord>& records) {
  if (!plan.section.lyapunov_spectrum) return 0;
  std::size_t dimension = 0;
  for (const auto& [key, record] : records)
    dimension = std::max(dimension, record.result.lyapunov_spectrum.size());
  return dimension;
}

void add_lyapunov_spectrum(std::vector<double>& columns, std::size_t dimension,
                           const SweepRecord& record) {
  const auto& exponents = record.result.lyapunov_spectrum;
  for (std::size_t i = 0; i < dimension; ++i)
    columns.push_back(i < exponents.size() ? exponents[i]
                                           : std::numeric_limits<double>::quiet_NaN());
}

SweepTable sweep_table(const SweepPlan& plan, const std::vector<SweepTask>& tasks,
                       const std::map<SweepRecordKey, SweepRecord>& records) {
  SweepTable table;
  table.lyapunov_dimension = lyapunov_dimension(plan, records);
  for (const SweepRecordKey& key : sweep_row_order(plan, tasks)) {
    const SweepRecord& r = records.at(key);
    add_lyapunov_spectrum(table.lyapunov_spectrum, table.lyapunov_dimension, r);
    table.value.push_back(plan.axes[0].value(r.index[0]));
    if (plan.axes.size() == 1) {
      add_bifurcation_rows(table, plan, r);
      table.direction.push_back(r.direction);
    } else {
      table.value2.push_back(plan.axes[1].value(r.index[1]));
      table.direction.push_back(1);
    }
    add_summary(table, r);
  }
  return table;
}

nlohmann::json sweep_counts(const std::map<SweepRecordKey, SweepRecord>& records) {
  std::uint64_t steps = 0, rhs = 0, stopped_points = 0, unsettled_points = 0;
  for (const auto& [key, record] : records) {
    steps += record.result.steps;
    rhs += record.result.rhs_evaluations;
    if (record.result.termination != SectionTermination::completed) ++stopped_points;
    if (record.result.transient_end == TransientEnd::not_settled) ++unsettled_points;
  }
  return {{"points", records.size()},
          {"points_stopped_early", stopped_points},
          {"points_not_settled", unsettled_points},
          {"steps", steps},
          {"rhs_evaluations", rhs}};
}

std::string stopped_points_note(const std::map<SweepRecordKey, SweepRecord>& records) {
  std::map<std::string_view, std::uint64_t> by_termination;
  std::uint64_t stopped = 0;
  for (const auto& [key, record] : records)
    if (record.result.termination != SectionTermination::completed) {
      ++by_termination[to_string(record.result.termination)];
      ++stopped;
    }
  if (stopped == 0) return {};
  std::string why;
  for (const auto& [termination, count] : by_termination)
    why += fmt::format("{}{} {}", why.empty() ? "" : ", ", termination, count);
  return fmt::format("{} of {} points stopped early ({})", stopped, records.size(), why);
}

std::string unsettled_points_note(const std::map<SweepRecordKey, SweepRecord>& records,
                                  const SweepPlan& plan) {
  const auto unsettled = std::count_if(records.begin(), records.end(), [](const auto& entry) {
    return entry.second.result.transient_end == TransientEnd::not_settled;
  });
  if (unsettled == 0) return {};
  return fmt::format(
      "{} of {} points did not settle within max_transient = {} forcing periods: their periods "
      "may be a transient's",
      unsettled, records.size(), plan.section.max_transient_periods);
}

}  // namespace impactlab
