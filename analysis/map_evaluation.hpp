// What an evaluation of a section map notes along the orbit it runs
// (OrbitEvaluation, continuation_problem.hpp), for the stroboscopic and the
// impact map alike: the virtual orbit with one wall's contacts suppressed
// (the grazing extended system's), the impacts, contact phases, impact
// signature and event times, and the lowest flight gap from samples of the
// orbit.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

// The system with witness `window.witness` suppressed in flight mode between
// the absolute times window.from and window.to, noting every crossing in
// flight mode into `trace` (where given): the grazing extended system.
template <HasJacobian System>
DecoratedSystem<System> suppressing_contacts(const System& system,
                                             typename System::Mode flight_mode,
                                             const ContactWindow& window, CrossingTrace* trace) {
  DecoratedSystem<System> decorated(system);
  decorated.with_suppressed_contacts(flight_mode, window, trace);
  return decorated;
}

// Samples of the wall gaps in flight, for the lowest flight gap.
template <class Base>
class GapSampler {
 public:
  using Mode = typename Base::Mode;
  GapSampler(const Base& base, Mode flight_mode, double t0, double spacing, int count)
      : base_(base), flight_mode_(flight_mode), t0_(t0), spacing_(spacing), count_(count) {}
  [[nodiscard]] double next_time() const {
    return next_ < count_ ? t0_ + (next_ + 1) * spacing_ : INFINITY;
  }
  template <class State>
  void observe(double t, const State& v, Mode mode) {
    ++next_;
    typename Base::State x;
    std::copy_n(v.begin(), x.size(), x.begin());
    Sample sample{t, mode == flight_mode_, {}};
    for (std::size_t k = 0; k < Base::max_witnesses; ++k)
      sample.gap[k] = k < base_.witness_count(mode) ? base_.witness(mode, k, x, t).value : INFINITY;
    samples.push_back(sample);
  }
  struct Sample {
    double t;
    bool flight;
    std::array<double, Base::max_witnesses> gap;
  };
  std::vector<Sample> samples;

 private:
  const Base& base_;
  Mode flight_mode_;
  double t0_, spacing_;
  int count_, next_ = 0;
};

// The impacts (and those that stick), contact phases, signature and event times (since t0) of the
// event records [begin, end) into `result`.
template <class Records>
void note_events(Records begin, Records end, double t0, OrbitEvaluation& result) {
  for (auto event = begin; event != end; ++event) {
    result.event_times.push_back(event->t - t0);
    const std::string wall = event->wall > 0 ? "+" + std::to_string(event->wall)
                                             : std::to_string(event->wall);
    if (event->kind == EventKind::impact) {
      ++result.impacts;
      if (event->sticks) ++result.stick_impacts;
      result.signature += (result.signature.empty() ? "" : " ") + wall;
    } else if (event->kind == EventKind::contact_start) {
      ++result.contact_phases;
      result.signature += (result.signature.empty() ? "c" : " c") + wall;
    }
  }
}

// The lowest interior local minimum of each gap between samples in flight,
// away from crossings, refined by the parabola through three samples.
template <class System, class Samples>
void note_lowest_flight_gap(const Samples& samples, const CrossingTrace& trace, double t0,
                            OrbitEvaluation& result) {
  for (std::size_t j = 1; j + 1 < samples.size(); ++j) {
    if (!samples[j - 1].flight || !samples[j].flight || !samples[j + 1].flight) continue;
    for (std::size_t k = 0; k < System::max_witnesses; ++k) {
      const double a = samples[j - 1].gap[k], b = samples[j].gap[k], c = samples[j + 1].gap[k];
      if (!(b <= a && b <= c) || !std::isfinite(a + b + c)) continue;
      const bool crossed = std::any_of(
          trace.crossings.begin(), trace.crossings.end(), [&](const auto& crossing) {
            return crossing.witness == static_cast<int>(k) && crossing.t >= samples[j - 1].t &&
                   crossing.t <= samples[j + 1].t;
          });
      if (crossed) continue;
      // the parabola through the three samples
      const double curvature = a - 2.0 * b + c;
      const double offset = curvature > 0.0 ? 0.5 * (a - c) / curvature : 0.0;
      const double lowest = b - 0.125 * (a - c) * offset;
      if (lowest < result.min_flight_gap) {
        result.min_flight_gap = lowest;
        result.min_flight_gap_time = samples[j].t + offset * (samples[j + 1].t - samples[j].t) - t0;
        result.min_flight_gap_witness = static_cast<int>(k);
      }
    }
  }
}

}  // namespace impactlab
