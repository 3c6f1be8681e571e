#include <impactlab/api/jin2003_reproduction.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>

#include <fmt/format.h>

#include <impactlab/api/model_spec.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/oscillators/pendulum_walls/sliding_impact.hpp>

namespace impactlab {

namespace {

std::vector<double> linear_grid(double from, double to, int points) {
  std::vector<double> grid(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i)
    grid[static_cast<std::size_t>(i)] =
        points == 1 ? from : from + (to - from) * static_cast<double>(i) / (points - 1);
  return grid;
}

Scene with_values(const Scene& scene, std::string_view model, double V0, double omega) {
  Scene changed = scene;
  apply_model(changed, model);
  apply_override(changed, fmt::format("V0={:.17g}", V0));
  apply_override(changed, fmt::format("omega={:.17g}", omega));
  return changed;
}

// the impact at `i` started a sliding phase: a contact phase begins at the
// same instant on the same wall
bool starts_sliding_phase(const std::vector<EventRecord>& events, std::size_t i) {
  return i + 1 < events.size() && events[i + 1].kind == EventKind::contact_start &&
         events[i + 1].t == events[i].t && events[i + 1].wall == events[i].wall;
}

struct ResidualTask {
  ResidualPanel* panel;
  std::string model;
  double value;
};

struct ResidualOutcome {
  std::vector<ResidualRow> rows;
  ParameterSummary summary;
};

ResidualOutcome run_residual_task(const Scene& scene, const Jin2003Settings& settings,
                                  const ResidualTask& task) {
  const bool over_omega = task.panel->parameter == "omega";
  const double V0 = over_omega ? task.panel->fixed_value : task.value;
  const double omega = over_omega ? task.value : task.panel->fixed_value;
  const Scene run_scene = with_values(scene, task.model, V0, omega);
  RunRequest request;
  request.periods = settings.periods;
  const RunOutput output = run_of_scene(run_scene, request);

  const double l = run_scene.number("l"), b = run_scene.number("b");
  const double cos0 = std::sqrt(1.0 - (b / l) * (b / l)), tan0 = (b / l) / cos0;
  const double e_n = run_scene.number("e_n"), e_t = run_scene.number("e_t");
  const double g = run_scene.number("g");

  ResidualOutcome outcome;
  outcome.summary = {task.value, task.model, output.impacts, 0, NAN, 0, output.termination};
  int impact_number = 0;
  double min_abs = INFINITY;
  for (std::size_t i = 0; i < output.events.size(); ++i) {
    const EventRecord& e = output.events[i];
    if (e.kind != EventKind::impact) continue;
    const int k = impact_number++ - settings.transient_impacts;
    if (k < 0) continue;
    if (k >= settings.recorded_impacts) break;
    ResidualRow row;
    row.parameter = task.value;
    row.model = task.model;
    row.k = k;
    row.t = e.t;
    row.wall = e.wall;
    row.normal_speed = l * cos0 * std::fabs(e.qdot_before);
    row.tangential_velocity = e.tangential_velocity;
    row.sliding_residual = sliding_condition_residual(V0, omega, g, e_t, e.tangential_velocity);
    row.instantaneous_residual =
        instantaneous_impact_residual(row.normal_speed, e.tangential_velocity, e_n, e_t, tan0);
    row.sliding_impact = starts_sliding_phase(output.events, i);
    outcome.rows.push_back(row);
    ++outcome.summary.recorded;
    if (row.sliding_impact) ++outcome.summary.sliding_impacts;
    if (!std::isnan(row.sliding_residual))
      min_abs = std::min(min_abs, std::fabs(row.sliding_residual));
  }
  if (std::isfinite(min_abs)) outcome.summary.min_abs_residual = min_abs;
  return outcome;
}

// Runs the tasks on `threads` threads; results land by task index, so the
// order never depends on the thread count.
template <class Task, class Outcome, class Work>
std::vector<Outcome> run_in_parallel(const std::vector<Task>& tasks, int threads, Work work,
                                     const std::function<void()>& on_done) {
  std::vector<Outcome> outcomes(tasks.size());
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const long count = static_cast<long>(tasks.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads)
  for (long i = 0; i < count; ++i) {
    try {
      outcomes[static_cast<std::size_t>(i)] = work(tasks[static_cast<std::size_t>(i)]);
    } catch (...) {
      const std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
    on_done();
  }
  if (failure) std::rethrow_exception(failure);
  return outcomes;
}

ResidualPanel make_panel(std::string parameter, std::string unit, std::string fixed,
                         double fixed_value, std::vector<double> grid) {
  ResidualPanel panel;
  panel.parameter = std::move(parameter);
  panel.unit = std::move(unit);
  panel.fixed = std::move(fixed);
  panel.fixed_value = fixed_value;
  panel.grid = std::move(grid);
  return panel;
}

// The time of the first steady-state impact (after the transient) of a run.
double steady_state_start(const RunOutput& output, int transient_impacts) {
  int impact_number = 0;
  for (const auto& e : output.events)
    if (e.kind == EventKind::impact && impact_number++ == transient_impacts) return e.t;
  return NAN;
}

SlipStatistics slip_statistics(const std::string& model, const std::vector<EventRecord>& events,
                               double from, double to) {
  SlipStatistics stats;
  stats.model = model;
  stats.window = to - from;
  double contact_since = NAN;
  double slip_total = 0.0;
  int slips_completed = 0;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const EventRecord& e = events[i];
    if (e.kind == EventKind::contact_start) contact_since = e.t;
    if (e.kind == EventKind::contact_end && !std::isnan(contact_since)) {
      const double overlap = std::min(e.t, to) - std::max(contact_since, from);
      if (overlap > 0.0) stats.time_on_walls += overlap;
      if (contact_since >= from && e.t <= to) {
        slip_total += e.t - contact_since;
        ++slips_completed;
      }
      contact_since = NAN;
    }
    if (e.t < from || e.t > to) continue;
    if (e.kind == EventKind::impact) ++stats.impacts;
    if (e.kind == EventKind::contact_start) {
      ++stats.contact_phases;
      if (i > 0 && events[i - 1].kind == EventKind::impact && events[i - 1].t == e.t)
        ++stats.sliding_impacts;
    }
  }
  if (slips_completed > 0) stats.mean_slip_duration = slip_total / slips_completed;
  return stats;
}

}  // namespace

Jin2003Results reproduce_jin2003(const Scene& scene, const Jin2003Settings& settings) {
  const auto start = std::chrono::steady_clock::now();
  Jin2003Results results;
  results.fig4a = make_panel("omega", "rad/s", "V0", settings.V0_of_fig4a,
                             linear_grid(settings.omega_from, settings.omega_to,
                                         settings.omega_points));
  results.fig4b = make_panel("V0", "m/s", "omega", settings.omega_of_fig4b,
                             linear_grid(settings.V0_from, settings.V0_to, settings.V0_points));

  std::vector<ResidualTask> tasks;
  for (ResidualPanel* panel : {&results.fig4a, &results.fig4b})
    for (const auto& model : settings.models)
      for (double value : panel->grid) tasks.push_back({panel, model, value});
  const double total_work = static_cast<double>(tasks.size() + 2 * settings.models.size());
  std::atomic<long> done{0};
  std::mutex progress_mutex;
  const std::function<void()> on_done = [&] {
    const long finished = ++done;
    if (!settings.progress) return;
    const std::lock_guard lock(progress_mutex);
    settings.progress(static_cast<double>(finished) / total_work);
  };

  const auto outcomes = run_in_parallel<ResidualTask, ResidualOutcome>(
      tasks, settings.threads,
      [&](const ResidualTask& task) { return run_residual_task(scene, settings, task); }, on_done);
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    ResidualPanel& panel = *tasks[i].panel;
    panel.rows.insert(panel.rows.end(), outcomes[i].rows.begin(), outcomes[i].rows.end());
    panel.summaries.push_back(outcomes[i].summary);
  }

  // Fig. 4(c, d): one run per model, sampled finely; the window starts after
  // the later of the models' transients, on a forcing-period boundary
  const Scene history_base =
      with_values(scene, settings.models.front(), settings.V0_of_history, settings.omega_of_history);
  const double period = history_base.forcing_period();
  const double sample_step = period / 2000.0;
  std::vector<RunOutput> histories(settings.models.size());
  double steady_from = 0.0;
  for (std::size_t m = 0; m < settings.models.size(); ++m) {
    const Scene run_scene = with_values(scene, settings.models[m], settings.V0_of_history,
                                        settings.omega_of_history);
    RunRequest request;
    request.periods = settings.periods + settings.history_periods;
    request.sample_step = sample_step;
    histories[m] = run_of_scene(run_scene, request);
    const double first_steady = steady_state_start(histories[m], settings.transient_impacts);
    steady_from = std::max(steady_from, std::isnan(first_steady) ? settings.periods * period
                                                                 : first_steady);
    on_done();
  }
  results.history_from = std::ceil(steady_from / period) * period;
  results.history_to = results.history_from + settings.history_periods * period;

  // the zoom: the first slip along a wall in the window, in the first model
  // that has one, with a tenth of a period on either side
  results.zoom_from = results.history_from;
  results.zoom_to = results.history_from + 0.5 * period;
  bool zoom_found = false;
  for (const auto& history : histories) {
    double since = NAN;
    for (const auto& e : history.events) {
      if (e.t < results.history_from) continue;
      if (e.kind == EventKind::contact_start) since = e.t;
      if (e.kind == EventKind::contact_end && !std::isnan(since)) {
        results.zoom_from = since - 0.1 * period;
        results.zoom_to = e.t + 0.1 * period;
        zoom_found = true;
        break;
      }
    }
    if (zoom_found) break;
  }

  const double l = scene.number("l");
  results.wall_position = scene.number("b");
  for (std::size_t m = 0; m < settings.models.size(); ++m) {
    const auto& samples = histories[m].samples;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const auto& s = samples[i];
      const HistorySample row{settings.models[m], s.t, l * std::sin(s.q), std::string(s.mode)};
      if (s.t >= results.history_from && s.t <= results.history_to && i % 10 == 0)
        results.fig4c.push_back(row);
      if (s.t >= results.zoom_from && s.t <= results.zoom_to) results.fig4d.push_back(row);
    }
    results.slips.push_back(slip_statistics(settings.models[m], histories[m].events,
                                            results.history_from, results.history_to));
    on_done();
  }
  results.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return results;
}

std::vector<ParameterRange> sliding_ranges(const ResidualPanel& panel, std::string_view model,
                                           double tolerance) {
  std::vector<ParameterRange> ranges;
  bool open = false;
  for (const auto& summary : panel.summaries) {
    if (summary.model != model) continue;
    const bool met = summary.min_abs_residual <= tolerance;  // false for NaN
    if (met && !open) ranges.push_back({summary.parameter, summary.parameter});
    if (met) ranges.back().to = summary.parameter;
    open = met;
  }
  return ranges;
}

const std::vector<double>& report_tolerances() {
  static const std::vector<double> tolerances = {0.01, 0.1, 0.5};
  return tolerances;
}

}  // namespace impactlab
