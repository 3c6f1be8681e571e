// Runs any hybrid system for a scene: resolves the time span and integrator
// from the scene, picks the stepper by name once, drives the event loop, and
// collects events, samples and counters into a RunOutput.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

namespace detail {

// Samples the trajectory at fixed intervals and reports progress at each
// hundredth of the run.
template <class ModeName>
class SamplingObserver {
 public:
  SamplingObserver(double t0, double t_end, const RunRequest& request, RunOutput& output,
                   ModeName mode_name)
      : t0_(t0), span_(t_end - t0), request_(request), output_(output), mode_name_(mode_name) {
    next_sample_ = request.sample_step > 0.0 ? t0 : INFINITY;
    next_progress_ = request.progress ? t0 + 0.01 * span_ : INFINITY;
  }

  [[nodiscard]] double next_time() const { return std::min(next_sample_, next_progress_); }

  template <class State, class Mode>
  void observe(double t, const State& x, Mode mode) {
    if (t >= next_sample_) {
      const TrajectorySample sample{t, x[0], x[1], mode_name_(mode)};
      if (request_.sample_sink)
        request_.sample_sink->write(sample);
      else
        output_.samples.push_back(sample);
      ++sample_index_;
      next_sample_ = t0_ + static_cast<double>(sample_index_) * request_.sample_step;
    }
    if (t >= next_progress_) {
      request_.progress((t - t0_) / span_);
      ++progress_index_;
      next_progress_ = progress_index_ >= 99 ? INFINITY
                                             : t0_ + 0.01 * static_cast<double>(progress_index_ + 1) * span_;
    }
  }

 private:
  double t0_, span_;
  const RunRequest& request_;
  RunOutput& output_;
  ModeName mode_name_;
  double next_sample_, next_progress_;
  long sample_index_ = 0, progress_index_ = 0;
};

}  // namespace detail

// Refuses, before anything runs, a time span that is not a finite interval
// after t0, or whose size passes the scene's limits: the steps it needs at the
// least (span / max_step, the system's longest step) over limits.max_steps,
// or its trajectory samples over limits.max_rows. BadInput names the option
// the user gave by its own name (`t_end`, `periods`, `sample`,
// api/job_options.hpp) or the scene key at fault.
inline void check_run_size(const RunRequest& request, const Scene& scene, double forcing_period,
                           double max_step) {
  const double t0 = scene.number("t0");
  const auto step_budget = static_cast<std::uint64_t>(scene.number("limits.max_steps"));
  const auto row_budget = static_cast<std::uint64_t>(scene.number("limits.max_rows"));
  const bool by_periods = request.periods > 0.0;
  const std::string length_key = by_periods ? "periods" : "t_end";
  const std::string length_value = fmt::format("{}", by_periods ? request.periods : request.t_end);
  if (by_periods && !(std::isfinite(forcing_period) && forcing_period > 0.0))
    throw BadInput("omega", scene.values.contains("omega") ? to_text(scene.values.at("omega")) : "",
                   fmt::format("the forcing period 2 pi/omega = {} is not a finite time",
                               forcing_period));
  const double t_end = by_periods ? t0 + request.periods * forcing_period : request.t_end;
  if (!std::isfinite(t_end))
    throw BadInput(length_key, length_value,
                   fmt::format("the end time t0 + span = {} s is not finite", t_end));
  if (by_periods && request.periods > 0.0 && !(t_end > t0))
    throw BadInput("t0", fmt::format("{}", t0),
                   fmt::format("time cannot advance here: {} periods ({:.3g} s) are below the "
                               "resolution of a double at t0 ({:.3g} s)",
                               request.periods, request.periods * forcing_period,
                               std::nextafter(t0, INFINITY) - t0));
  if (!(t_end > t0))
    throw BadInput(length_key, length_value,
                   fmt::format("the end time {} s must be after t0 = {} s", t_end, t0));
  const double span = t_end - t0;
  const double least_steps = std::isfinite(max_step) && max_step > 0.0 ? span / max_step : 0.0;
  if (least_steps > static_cast<double>(step_budget))
    throw BadInput(length_key, length_value,
                   fmt::format("needs at least {:.3g} steps, over limits.max_steps = {} (raise "
                               "it with `set` limits.max_steps=N)",
                               least_steps, step_budget));
  if (request.sample_step > 0.0) {
    const double rows = span / request.sample_step;
    if (!(rows <= static_cast<double>(row_budget)))
      throw BadInput("sample", fmt::format("{}", request.sample_step),
                     fmt::format("would write {:.3g} rows, over limits.max_rows = {} (raise it "
                                 "with `set` limits.max_rows=N)",
                                 rows, row_budget));
  }
}

// forcing_period: the scene's natural time unit for `periods` (s).
// mode_name: Mode -> std::string_view, for the trajectory's mode column.
template <HybridSystem System, class ModeName>
RunOutput run_system(const System& system, const typename System::State& x0,
                     typename System::Mode mode0, const Scene& scene, const RunRequest& request,
                     double forcing_period, ModeName mode_name) {
  RunOutput output;
  output.t0 = scene.number("t0");
  check_run_size(request, scene, forcing_period, system.max_step());
  output.t_end = request.periods > 0.0 ? output.t0 + request.periods * forcing_period
                                       : request.t_end;

  StepperSettings settings;
  settings.rtol = scene.number("integrator.rtol");
  settings.atol = scene.number("integrator.atol");
  settings.max_step = system.max_step();
  LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  options.step_budget = static_cast<std::uint64_t>(scene.number("limits.max_steps"));

  EventLog log(request.keep_events, request.event_sink);
  if (request.keep_events) log.reserve(1024);
  detail::SamplingObserver<ModeName> observer(output.t0, output.t_end, request, output, mode_name);

  const auto start = std::chrono::steady_clock::now();
  const auto result = with_flow<System>(
      scene.text("integrator.method"), settings, [&](auto& stepper) {
        return simulate(system, stepper, x0, mode0, output.t0, output.t_end, options, log,
                        observer);
      });
  output.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  output.events = log.records();
  output.event_count = log.total();
  if (const EventRecord* last = log.last()) output.last_event = *last;
  output.largest_accumulation_error = log.largest_accumulation_error();
  output.t_final = result.t;
  output.termination = result.termination;
  output.steps = result.counters.steps;
  output.rhs_evaluations = result.counters.rhs_evaluations;
  output.impacts = log.count(EventKind::impact);
  output.contact_phases = log.count(EventKind::contact_start);
  output.accumulations = log.count(EventKind::accumulation);
  output.grazings = log.count(EventKind::grazing);
  return output;
}

}  // namespace impactlab
