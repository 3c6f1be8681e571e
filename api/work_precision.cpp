#include <impactlab/api/work_precision.hpp>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <stdexcept>

#include <boost/multiprecision/cpp_bin_float.hpp>

#include <impactlab/api/bindings/pendulum_walls_parameters.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/api/visit_scene.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include <impactlab/platform/sample_median.hpp>

namespace impactlab {

namespace {

// std::to_string prints 6 decimals: tolerances need the exponent form
std::string exact_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

Scene with_tolerances(Scene scene, const std::string& method, double rtol, double atol) {
  apply_override(scene, "integrator.method=" + method);
  apply_override(scene, "integrator.rtol=" + exact_text(rtol));
  apply_override(scene, "integrator.atol=" + exact_text(atol));
  return scene;
}

// CPU time of the calling thread (s): on a shared machine, the work of one
// core, unlike wall time, does not grow with the other processes' load
double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace

std::vector<ImpactSample> impacts_of(const std::vector<EventRecord>& events) {
  std::vector<ImpactSample> impacts;
  for (const auto& event : events)
    if (event.kind == EventKind::impact) impacts.push_back({event.t, event.qdot_before});
  return impacts;
}

ImpactErrors impact_errors(const ReferenceImpacts& reference,
                           const std::vector<ImpactSample>& run) {
  ImpactErrors errors;
  errors.reference = reference.impacts.size();
  errors.compared = std::min(reference.impacts.size(), run.size());
  for (std::size_t i = 0; i < errors.compared; ++i) {
    errors.time = std::max(errors.time, std::fabs(run[i].t - reference.impacts[i].t));
    errors.velocity =
        std::max(errors.velocity, std::fabs(run[i].qdot_before - reference.impacts[i].qdot_before));
  }
  return errors;
}

ReferenceImpacts closed_form_reference(const Scene& scene, double t_end, std::size_t max_impacts) {
  ReferenceImpacts reference;
  reference.method = "closed_form";
  const double t0 = scene.number("t0");
  reference.impacts = visit_scene(
      scene, [&]<class Binding>(const SceneSystem<Binding>& bound) -> std::vector<ImpactSample> {
        if constexpr (HasExactFlow<typename Binding::System>)
          return closed_form_impacts(bound.system(), bound.initial_state(), bound.flight_mode(),
                                     t0, t_end, max_impacts);
        else
          throw std::invalid_argument("closed_form_reference: no closed form for " +
                                      scene.oscillator);
      });
  reference.impacts_computed = reference.impacts.size();
  return reference;
}

std::vector<ImpactSample> extended_precision_reference(const Scene& scene, double t_end,
                                                       double tolerance) {
  if (scene.oscillator != "pendulum_walls" || scene.text("model") != "newton")
    throw std::invalid_argument("extended_precision_reference: pendulum_walls, model newton only");
  using Quad = boost::multiprecision::cpp_bin_float_quad;
  const PendulumWalls system(pendulum_walls_parameters(scene));
  StepperSettings settings;
  settings.rtol = tolerance;
  settings.atol = tolerance;
  settings.max_step = system.max_step();
  LoopOptions options;
  options.location.grazing_tolerance = tolerance;
  EventLog log;
  TaylorStepper<PendulumWalls, Quad> stepper(settings);
  const PendulumWalls::State x0 = {scene.number("initial.theta"), scene.number("initial.theta_dot"),
                                   0.0};
  const auto result =
      simulate(system, stepper, x0, PendulumMode::free, scene.number("t0"), t_end, options, log);
  if (result.termination != Termination::completed)
    throw std::runtime_error("extended_precision_reference: the run stopped: " +
                             std::string(to_string(result.termination)));
  return impacts_of(log.records());
}

ReferenceImpacts integrated_reference(const Scene& scene, double t_end, std::size_t max_impacts,
                                      const std::vector<std::string>& methods,
                                      double trusted_time_spread) {
  if (methods.empty()) throw std::invalid_argument("integrated_reference: no methods");
  std::vector<std::vector<ImpactSample>> runs;
  for (const auto& method : methods) {
    if (method == "taylor_quad") {
      runs.push_back(extended_precision_reference(scene, t_end));
      continue;
    }
    const Scene tight = with_tolerances(scene, method, 1e-14, 1e-16);
    RunRequest request;
    request.periods = 0.0;
    request.t_end = t_end;
    const RunOutput output = run_of_scene(tight, request);
    runs.push_back(impacts_of(output.events));
  }
  ReferenceImpacts reference;
  for (const auto& method : methods) reference.method += (reference.method.empty() ? "" : "+") + method;
  reference.impacts_computed = runs.front().size();
  std::size_t trusted = std::min(max_impacts, runs.front().size());
  for (const auto& run : runs) trusted = std::min(trusted, run.size());
  // the leading impacts where every method agrees
  for (std::size_t i = 0; i < trusted; ++i) {
    double time_spread = 0.0, velocity_spread = 0.0;
    for (const auto& run : runs) {
      time_spread = std::max(time_spread, std::fabs(run[i].t - runs.front()[i].t));
      velocity_spread =
          std::max(velocity_spread, std::fabs(run[i].qdot_before - runs.front()[i].qdot_before));
    }
    if (time_spread > trusted_time_spread) {
      trusted = i;
      break;
    }
    reference.time_spread = std::max(reference.time_spread, time_spread);
    reference.velocity_spread = std::max(reference.velocity_spread, velocity_spread);
  }
  reference.impacts.assign(runs.front().begin(), runs.front().begin() + trusted);
  return reference;
}

WorkPrecisionPoint measure_point(const Scene& scene, const std::string& method, double rtol,
                                 double atol, double periods, int repetitions,
                                 const ReferenceImpacts& reference) {
  const Scene run_scene = with_tolerances(scene, method, rtol, atol);
  WorkPrecisionPoint point;
  point.method = method;
  point.rtol = rtol;
  point.atol = atol;
  std::vector<double> cpu_seconds, wall_seconds;
  for (int repetition = 0; repetition < std::max(repetitions, 1); ++repetition) {
    // thread CPU time at each hundredth of the simulated time, for the first
    // and last tenth of the run
    std::vector<double> stamps;
    stamps.reserve(128);
    RunRequest request;
    request.periods = periods;
    request.progress = [&stamps](double) { stamps.push_back(thread_cpu_seconds()); };
    const double start = thread_cpu_seconds();
    const RunOutput output = run_of_scene(run_scene, request);
    cpu_seconds.push_back(thread_cpu_seconds() - start);
    wall_seconds.push_back(output.wall_time);
    if (repetition > 0) continue;

    const std::vector<ImpactSample> impacts = impacts_of(output.events);
    point.impacts = impacts.size();
    point.termination = to_string(output.termination);
    const double per_impact = impacts.empty() ? 0.0 : 1.0 / static_cast<double>(impacts.size());
    point.rhs_per_impact = static_cast<double>(output.rhs_evaluations) * per_impact;
    point.steps_per_impact = static_cast<double>(output.steps) * per_impact;
    point.errors = impact_errors(reference, impacts);

    // stamps[k] is taken at t0 + (k + 1)/100 of the span
    // (the last stamp is at 0.99, so the last tenth measured is 0.89 .. 0.99)
    if (stamps.size() >= 99) {
      const double span = output.t_end - output.t0;
      auto impacts_between = [&](double from, double to) {
        return std::count_if(impacts.begin(), impacts.end(), [&](const ImpactSample& s) {
          return s.t >= output.t0 + from * span && s.t < output.t0 + to * span;
        });
      };
      const auto first = impacts_between(0.0, 0.1);
      const auto last = impacts_between(0.89, 0.99);
      if (first > 0)
        point.first_tenth_seconds_per_impact = (stamps[9] - start) / static_cast<double>(first);
      if (last > 0)
        point.last_tenth_seconds_per_impact =
            (stamps[98] - stamps[88]) / static_cast<double>(last);
    }
  }
  if (point.impacts > 0) {
    point.seconds_per_impact = median(cpu_seconds) / static_cast<double>(point.impacts);
    point.wall_seconds_per_impact = median(wall_seconds) / static_cast<double>(point.impacts);
  }
  return point;
}

std::vector<WorkPrecisionPoint> pareto_front(const std::vector<WorkPrecisionPoint>& points) {
  std::vector<WorkPrecisionPoint> sorted;
  for (const auto& point : points)
    if (std::isfinite(point.seconds_per_impact) && std::isfinite(point.errors.time))
      sorted.push_back(point);
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.errors.time < b.errors.time ||
           (a.errors.time == b.errors.time && a.seconds_per_impact < b.seconds_per_impact);
  });
  std::vector<WorkPrecisionPoint> front;
  double cheapest = INFINITY;
  for (const auto& point : sorted) {
    if (point.seconds_per_impact < cheapest) {
      front.push_back(point);
      cheapest = point.seconds_per_impact;
    }
  }
  return front;
}

const WorkPrecisionPoint* cheapest_within(const std::vector<WorkPrecisionPoint>& points,
                                          double max_time_error) {
  const WorkPrecisionPoint* best = nullptr;
  for (const auto& point : points) {
    if (!point.errors.complete() || !(point.errors.time <= max_time_error) ||
        !std::isfinite(point.seconds_per_impact))
      continue;
    if (!best || point.seconds_per_impact < best->seconds_per_impact) best = &point;
  }
  return best;
}

std::vector<SpeedRatio> speed_ratios(const std::vector<WorkPrecisionPoint>& slow,
                                     const std::vector<WorkPrecisionPoint>& fast) {
  std::vector<SpeedRatio> ratios;
  for (const auto& point : slow) {
    const WorkPrecisionPoint* match = cheapest_within(fast, point.errors.time);
    if (!match || !std::isfinite(point.seconds_per_impact)) continue;
    ratios.push_back({point.errors.time, match->errors.time, point.method, match->method,
                      point.rtol, match->rtol,
                      point.seconds_per_impact / match->seconds_per_impact});
  }
  return ratios;
}

bool has_closed_form(const Scene& scene) {
  return visit_scene(scene, []<class Binding>(const SceneSystem<Binding>&) {
    return HasExactFlow<typename Binding::System>;
  });
}

ReferenceImpacts bench_reference(const Scene& scene, double t_end, std::size_t max_impacts) {
  if (has_closed_form(scene)) return closed_form_reference(scene, t_end, max_impacts);
  // the quad-precision Taylor run exists for the pendulum's Model N only
  const bool quad = scene.oscillator == "pendulum_walls" && scene.text("model") == "newton";
  return integrated_reference(scene, t_end, max_impacts,
                              quad ? std::vector<std::string>{"taylor_quad", "rk8pd"}
                                   : std::vector<std::string>{"rk8pd", "bulirsch_stoer"},
                              1e-10);
}

}  // namespace impactlab
