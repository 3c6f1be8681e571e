// One run of a concrete system onto a Poincaré section: discard a transient
// (forcing periods, or impacts), record the section points, count impacts and
// contact phases in the record window, optionally the largest Lyapunov
// exponent, and return the final state for continuation. Each oscillator's
// binding runs it through section_of_scene (api/system_jobs.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>

#include <fmt/format.h>

#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/lyapunov_spectrum.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/analysis/settling.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

namespace detail {

// Observes the state at the stroboscopic times t_k = (phase + 2πk)/ω.
class StrobeObserver {
 public:
  StrobeObserver(double omega, double phase, double from, std::uint64_t count,
                 SectionPoints& points)
      : omega_(omega), phase_(phase), count_(count), points_(points) {
    // first k with t_k >= from (to round-off)
    first_ = std::ceil((omega * from - phase) / (2.0 * std::numbers::pi) - 1e-9);
  }
  [[nodiscard]] double next_time() const {
    if (taken_ >= count_) return INFINITY;
    return (phase_ + 2.0 * std::numbers::pi * (first_ + static_cast<double>(taken_))) / omega_;
  }
  template <class State, class Mode>
  void observe(double t, const State& x, Mode) {
    points_.add({t, x[0], x[1], 0});
    ++taken_;
  }
  [[nodiscard]] double last_time() const {
    return (phase_ + 2.0 * std::numbers::pi * (first_ + static_cast<double>(count_) - 1.0)) /
           omega_;
  }

 private:
  double omega_, phase_, first_;
  std::uint64_t count_, taken_ = 0;
  SectionPoints& points_;
};

// Reports a run's progress once per forcing period (at t0 + k·period), at
// the dense output beside the stretch's own observer `Inner`: the steps
// are those of a run without it. The fraction is the time run over `span`,
// at most 1; `report` may throw to stop the run.
template <class Inner>
class ProgressObserver {
 public:
  ProgressObserver(const std::function<void(double)>& report, double t0, double period,
                   double span, double from, Inner& inner)
      : report_(report), t0_(t0), period_(period), span_(span), inner_(inner) {
    // first k with t0 + k·period > from
    next_report_ = t0 + period * (std::floor((from - t0) / period) + 1.0);
  }
  [[nodiscard]] double next_time() const { return std::min(inner_.next_time(), next_report_); }
  template <class State, class Mode>
  void observe(double t, const State& x, Mode mode) {
    if (t >= inner_.next_time()) inner_.observe(t, x, mode);
    if (t >= next_report_) {
      next_report_ += period_;
      report_(std::clamp((t - t0_) / span_, 0.0, 1.0));
    }
  }

 private:
  const std::function<void(double)>& report_;
  double t0_, period_, span_, next_report_;
  Inner& inner_;
};

// A time span in forcing periods, whole where it is one up to the round-off
// of the time sums.
inline double periods_in(double span, double period) {
  const double periods = span / period;
  return std::fabs(periods - std::round(periods)) < 1e-6 ? std::round(periods) : periods;
}

}  // namespace detail

// x0, mode0: the scene's initial state; omega: the forcing frequency (rad per
// time unit); admissible(State&, Mode&): moves a continued state into the
// current parameters' admissible set (walls may have moved).
template <HybridSystem System, class Admissible>
SectionResult run_section(const System& system, const typename System::State& x0,
                          typename System::Mode mode0, const Scene& scene,
                          const SectionRequest& request, double omega, Admissible admissible) {
  using State = typename System::State;
  using Mode = typename System::Mode;
  SectionResult result;
  result.omega = omega;
  // N exponents asked for: NaN until computed (a run that stops early keeps them)
  if (request.lyapunov_spectrum) {
    result.lyapunov_spectrum.assign(tangent_dimension_of<System>,
                                    std::numeric_limits<double>::quiet_NaN());
    result.lyapunov_spectrum_error = result.lyapunov_spectrum;
  }
  result.forcing_period = 2.0 * std::numbers::pi / omega;
  const double period = result.forcing_period;
  // the transient and record at the request's stepper where it names one;
  // the Lyapunov run always at the scene's integrator
  FlowSetup lyapunov_setup = flow_setup(scene);
  lyapunov_setup.series_lane = request.series_lane;
  const FlowSetup setup =
      request.integrator ? with_integrator(lyapunov_setup, *request.integrator) : lyapunov_setup;
  check_section_size(request, omega, system.max_step(), setup.step_budget);
  const LoopOptions options = loop_options(setup);

  State x = x0;
  Mode mode = mode0;
  if (request.start && request.start->state.size() == std::tuple_size_v<State>) {
    std::copy(request.start->state.begin(), request.start->state.end(), x.begin());
    mode = static_cast<Mode>(request.start->mode);
    admissible(x, mode);
  }
  double t = scene.number("t0");
  const double t0 = t;

  return with_flow<System>(setup.method, stepper_settings(system, setup), [&](auto& stepper) {
    // one stretch of the run, from (t, x, mode) to t_end; false when it stopped early
    // (with the request's progress reports, once per forcing period, where it has them)
    const double progress_span =
        std::max(request.transient_periods + static_cast<double>(request.points), 1.0) * period;
    auto advance = [&](double t_end, EventLog& log, auto&& observer) {
      const auto run =
          request.progress
              ? simulate(system, stepper, x, mode, t, t_end, options, log,
                         detail::ProgressObserver(request.progress, t0, period, progress_span, t,
                                                  observer))
              : simulate(system, stepper, x, mode, t, t_end, options, log, observer);
      result.steps += run.counters.steps;
      result.rhs_evaluations += run.counters.rhs_evaluations;
      x = run.state;
      mode = run.mode;
      t = run.t;
      if (run.termination == Termination::completed) return true;
      result.termination = section_termination(run.termination);
      return false;
    };
    const auto max_periods = static_cast<std::uint64_t>(request.max_periods);

    // transient: whole periods, or periods until the stroboscopic points
    // settle, or periods until enough impacts
    EventLog transient_log(false);
    if (request.transient_impacts == 0 && !request.settle) {
      if (request.transient_periods > 0.0 &&
          !advance(t0 + request.transient_periods * period, transient_log, NoObserver{}))
        return result;
    } else if (request.transient_impacts == 0) {
      // the least transient with its last window observed (dense output: the
      // steps are those of a run without the observer), then one window at a
      // time while the points still converge
      const double phase =
          request.section.kind == SectionKind::strobe ? request.section.phase : 0.0;
      const auto window_periods = static_cast<std::uint64_t>(request.settle_window_periods);
      std::vector<SectionPoint> window;
      double periods_run = std::max(request.transient_periods, 0.0);
      auto run_window = [&](double to_periods) {
        window.clear();
        SectionPoints observed(window, nullptr, window_periods);
        const double from =
            std::max(t0 + (to_periods - static_cast<double>(window_periods)) * period, t);
        detail::StrobeObserver observer(omega, phase, from, window_periods, observed);
        return advance(t0 + to_periods * period, transient_log, observer);
      };
      if (periods_run > 0.0 && !run_window(periods_run)) return result;
      for (;;) {
        const SettlingVerdict verdict =
            window.size() < 4 ? SettlingVerdict::converging
                              : settling_verdict(window, request.settle_max_period,
                                                 request.settle_tolerance);
        if (verdict == SettlingVerdict::settled) {
          result.transient_end = TransientEnd::settled;
          break;
        }
        if (verdict == SettlingVerdict::not_periodic) {
          result.transient_end = TransientEnd::not_periodic;
          break;
        }
        if (periods_run + static_cast<double>(window_periods) > request.max_transient_periods) {
          result.transient_end = TransientEnd::not_settled;
          break;
        }
        periods_run += static_cast<double>(window_periods);
        if (!run_window(periods_run)) return result;
      }
    } else {
      for (std::uint64_t k = 1; transient_log.count(EventKind::impact) < request.transient_impacts;
           ++k) {
        if (k > max_periods) {
          result.termination = SectionTermination::transient_impacts_not_reached;
          return result;
        }
        if (!advance(t0 + static_cast<double>(k) * period, transient_log, NoObserver{}))
          return result;
      }
    }
    result.record_start = t;
    result.transient_periods = detail::periods_in(t - t0, period);
    const State x_record = x;
    const Mode mode_record = mode;

    // record
    EventLog record_log(request.section.kind == SectionKind::impact);
    SectionPoints collected(result.points, request.point_sink, request.points);
    if (request.point_sink != nullptr) request.point_sink->begin(omega);
    if (request.section.kind == SectionKind::strobe) {
      detail::StrobeObserver observer(omega, request.section.phase, t, request.points, collected);
      const double end = std::max(t + static_cast<double>(request.points) * period,
                                  observer.last_time());
      if (!advance(end, record_log, observer)) {
        result.point_count = collected.count();
        return result;
      }
    } else if (request.section.kind != SectionKind::impact) {
      // a user-given section: the system with one more witness, in whole periods
      DecoratedSystem<System> crossing(system);
      crossing.with_crossing_section(request.section, collected);
      const std::uint64_t chunk = std::max<std::uint64_t>(request.points, 1);
      for (std::uint64_t periods = 0; !collected.full(); periods += chunk) {
        if (periods >= max_periods) {
          result.termination = SectionTermination::crossings_not_reached;
          break;
        }
        const auto run = with_flow<DecoratedSystem<System>>(
            setup.method, stepper_settings(system, setup), [&](auto& crossing_stepper) {
              return simulate(crossing, crossing_stepper, x, mode, t,
                              t + static_cast<double>(chunk) * period, options, record_log);
            });
        result.steps += run.counters.steps;
        result.rhs_evaluations += run.counters.rhs_evaluations;
        x = run.state;
        mode = run.mode;
        t = run.t;
        if (run.termination != Termination::completed) {
          result.termination = section_termination(run.termination);
          break;
        }
        if (request.progress) request.progress(std::min((t - t0) / progress_span, 1.0));
      }
    } else {
      const std::uint64_t chunk = std::max<std::uint64_t>(request.points, 1);
      for (std::uint64_t periods = 0; !collected.full(); periods += chunk) {
        if (periods >= max_periods) {
          result.termination = SectionTermination::impacts_not_reached;
          break;
        }
        if (!advance(t + static_cast<double>(chunk) * period, record_log, NoObserver{})) break;
        for (const auto& event : record_log.records())
          if (event.kind == EventKind::impact &&
              (request.section.wall == 0 || event.wall == request.section.wall) &&
              event.t > collected.last_time())
            collected.add({event.t, event.q, event.qdot_before, event.wall});
        record_log.clear_records();
      }
    }
    result.point_count = collected.count();
    result.periods_recorded = detail::periods_in(t - result.record_start, period);
    result.impacts = record_log.count(EventKind::impact);
    result.stick_impacts = record_log.stick_impacts();
    if (result.impacts > 0) result.min_impact_speed = record_log.smallest_impact_speed();
    result.contact_phases =
        std::max(record_log.count(EventKind::contact_start), record_log.count(EventKind::contact_end));
    // mode 0 is every system's free flight
    result.rests_in_contact = result.contact_phases == 0 && static_cast<int>(mode_record) != 0 &&
                              static_cast<int>(mode) != 0;
    if (result.termination == SectionTermination::completed)
      result.final_state = ContinuationState{std::vector<double>(x.begin(), x.end()),
                                             static_cast<int>(mode)};

    // all N exponents over the record window, from its start; their λ1 is
    // the largest exponent (the same first vector, carried the same way), so
    // where both are asked for one tangent run gives both
    if (request.lyapunov_spectrum) {
      if constexpr (HasJacobian<System>) {
        const int periods = std::max(1, static_cast<int>(std::lround(result.periods_recorded)));
        const LyapunovSpectrumResult spectrum = lyapunov_spectrum(
            system, lyapunov_setup, x_record, mode_record, result.record_start, period, periods,
            request.lyapunov_alignment_periods, request.lyapunov_spectrum_sink);
        result.lyapunov_spectrum = spectrum.exponents;
        result.lyapunov_spectrum_error = spectrum.errors;
        if (spectrum.termination == Termination::no_tangent_map)
          result.lyapunov_spectrum_note = "an event on the way has no tangent map (an impulse on "
                                          "the friction cone's edge)";
        else if (spectrum.termination != Termination::completed)
          result.lyapunov_spectrum_note = fmt::format(
              "the tangent run stopped early ({})", to_string(spectrum.termination));
        if (request.lyapunov) {
          result.lyapunov = spectrum.exponents.front();
          result.lyapunov_note = result.lyapunov_spectrum_note;
        }
      } else {
        result.lyapunov_spectrum_note = "this oscillator/model has no Jacobians";
        if (request.lyapunov) result.lyapunov_note = result.lyapunov_spectrum_note;
      }
      return result;
    }

    // the largest Lyapunov exponent over the record window, from its start
    if (request.lyapunov) {
      if constexpr (HasJacobian<System>) {
        const int periods = std::max(1, static_cast<int>(std::lround(result.periods_recorded)));
        const LyapunovResult lyapunov = largest_lyapunov_exponent(
            system, lyapunov_setup, x_record, mode_record, result.record_start, period, periods,
            request.lyapunov_alignment_periods);
        result.lyapunov = lyapunov.exponent;
        if (lyapunov.termination == Termination::no_tangent_map)
          result.lyapunov_note = "an event on the way has no tangent map (an impulse on the "
                                 "friction cone's edge)";
        else if (lyapunov.termination != Termination::completed)
          result.lyapunov_note = "the tangent run stopped early";
      } else {
        result.lyapunov_note = "this oscillator/model has no Jacobians";
      }
    }
    return result;
  });
}

}  // namespace impactlab
