// Poincaré sections: which section, what one point on it records, and what
// one run onto a section is asked for and gives back. These types are
// independent of the oscillator, so that commands and sweeps reach every
// oscillator through one type-erased entry (api/system_jobs.hpp's section_of_scene,
// analysis/run_section.hpp does the work for a concrete system).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/integrate/series_lane.hpp>
#include <impactlab/simulate/termination.hpp>

namespace impactlab {

enum class SectionKind {
  strobe,  // stroboscopic: the state where the forcing phase ωt (mod 2π) equals `phase`
  impact,  // the impact map: the state just before each impact with `wall`
  q_crossing,     // a user-given section: q = level, crossed in `direction`
  qdot_crossing,  // a user-given section: q̇ = level, crossed in `direction`
};

struct SectionSpec {
  SectionKind kind = SectionKind::strobe;
  double phase = 0.0;  // rad in [0, 2π): the forcing phase of a stroboscopic section
  int wall = 0;        // impact map: +1 / -1, or 0 for every wall
  double level = 0.0;  // user-given section: the value of q or q̇
  int direction = 1;   // user-given section: +1 increasing, −1 decreasing, 0 both
};

// Parses `strobe[:PHASE]`, `impact[:WALL]` (WALL: +1, -1, 1, or 0 for any),
// `q=LEVEL[:up|down|both]` or `qdot=LEVEL[:up|down|both]` (default up);
// BadInput (key `key`) otherwise.
SectionSpec parse_section(std::string_view text, std::string_view key);
std::string to_string(const SectionSpec& section);

// One point on a section.
struct SectionPoint {
  double t = 0.0;     // time (s, or the scene's time unit)
  double q = 0.0;     // main coordinate (θ, x or y)
  double qdot = 0.0;  // its rate (before the impact, for the impact map)
  int wall = 0;       // impact map: the wall hit; 0 for a stroboscopic point
};

// Where a run's section points go as they are found, instead of
// SectionResult::points: a long record written straight to its file keeps
// the run's memory independent of its length.
class SectionPointSink {
 public:
  virtual ~SectionPointSink() = default;
  // the run's forcing frequency ω (rad per time unit), before its first point
  virtual void begin(double omega) = 0;
  virtual void write(const SectionPoint& point) = 0;
};

// Where the running estimate of a Lyapunov spectrum goes, once per averaged
// forcing period (analysis/lyapunov_spectrum.hpp): lyapunov.csv's rows.
class LyapunovSpectrumSink {
 public:
  virtual ~LyapunovSpectrumSink() = default;
  // the number of exponents N, before the first row
  virtual void begin(std::size_t exponents) = 0;
  // the time at the end of the period (time unit) and each exponent's
  // estimate over the periods averaged so far (1/time unit; −∞ collapsed)
  virtual void write(double t, const std::vector<double>& running) = 0;
};

// The points of one record, at most `limit`: appended to `points`, or handed
// to `sink` when there is one.
class SectionPoints {
 public:
  SectionPoints(std::vector<SectionPoint>& points, SectionPointSink* sink, std::uint64_t limit)
      : points_(points), sink_(sink), limit_(limit) {}
  void add(const SectionPoint& point) {
    if (count_ >= limit_) return;
    ++count_;
    last_time_ = point.t;
    if (sink_ != nullptr) {
      sink_->write(point);
    } else {
      points_.push_back(point);
    }
  }
  [[nodiscard]] std::uint64_t count() const { return count_; }
  [[nodiscard]] bool full() const { return count_ >= limit_; }
  [[nodiscard]] double last_time() const { return last_time_; }  // -inf before the first

 private:
  std::vector<SectionPoint>& points_;
  SectionPointSink* sink_;
  std::uint64_t limit_, count_ = 0;
  double last_time_ = -std::numeric_limits<double>::infinity();
};

// The state a run ends in, to continue from at the next parameter value.
struct ContinuationState {
  std::vector<double> state;  // the system's whole state
  int mode = 0;               // the system's mode, as its enum's integer value
};

// An integrator as a scene states it (integrator.method, integrator.rtol,
// integrator.atol).
struct IntegratorSetting {
  std::string method;
  double rtol = 0.0;  // relative error per step (dimensionless)
  double atol = 0.0;  // absolute error per step (state units)
};

// How a run's transient ended (analysis/settling.hpp says when points settle).
enum class TransientEnd {
  fixed,         // after the periods or impacts asked for, with no settling test
  settled,       // the stroboscopic points repeat to the settling tolerance
  not_periodic,  // they neither repeat nor converge: chaos, a torus, a longer period
  not_settled,   // still converging when max_transient_periods ran out
};

constexpr std::string_view to_string(TransientEnd end) {
  switch (end) {
    case TransientEnd::fixed: return "fixed";
    case TransientEnd::settled: return "settled";
    case TransientEnd::not_periodic: return "not_periodic";
    case TransientEnd::not_settled: return "not_settled";
  }
  return "fixed";
}

// The end named `text` (a sweep checkpoint's); none for another word.
constexpr std::optional<TransientEnd> parse_transient_end(std::string_view text) {
  for (TransientEnd end : {TransientEnd::fixed, TransientEnd::settled,
                           TransientEnd::not_periodic, TransientEnd::not_settled})
    if (to_string(end) == text) return end;
  return std::nullopt;
}

struct SectionRequest {
  SectionSpec section;
  // forcing periods discarded first: exactly these with `settle` false; with
  // it, at least these, then windows of settle_window_periods until the
  // stroboscopic points settle, at most max_transient_periods in all
  double transient_periods = 100.0;
  bool settle = true;
  double max_transient_periods = 2000.0;
  int settle_window_periods = 64;
  double settle_tolerance = 1e-7;      // relative, as the sweep's period tolerance
  int settle_max_period = 16;          // longest period the settling test looks for
  std::uint64_t transient_impacts = 0; // when > 0: discard this many impacts instead (no settling)
  std::uint64_t points = 50;           // strobe: periods recorded; impact: impacts recorded
  bool lyapunov = false;               // also the largest Lyapunov exponent
  int lyapunov_alignment_periods = 10; // periods a tangent vector turns before averaging
  bool lyapunov_spectrum = false;      // also all N exponents (analysis/lyapunov_spectrum.hpp)
  // where the spectrum's running estimate goes, period by period; none: not kept
  LyapunovSpectrumSink* lyapunov_spectrum_sink = nullptr;
  // the transient's and record's stepper where it is not the scene's (a sweep
  // that only classifies, analysis/sweep.hpp); the system itself (its
  // accumulation criteria) and the Lyapunov run keep the scene's integrator
  std::optional<IntegratorSetting> integrator;
  double max_periods = 1e5;            // cap on a transient or record counted in impacts
  std::optional<ContinuationState> start;  // instead of the scene's initial state
  // where the points go as they are found; none: SectionResult::points
  SectionPointSink* point_sink = nullptr;
  // the fraction of the run done (0..1), once per forcing period of the
  // transient and the record (for a stroboscopic section: once per point),
  // at a dense-output evaluation: the steps, events and points are those of
  // a run without it, but a stepper whose dense output evaluates the
  // right-hand side (rkf78; not Taylor) counts those in rhs_evaluations.
  // It may throw to stop the run (a superseded explorer job), and the
  // exception leaves run_section. The fraction is the time run over
  // transient_periods + points periods, at most 1: exact for a
  // stroboscopic section with a fixed transient, an estimate otherwise.
  // None: no reports (the CLI's and Python's poincare pass none, so that
  // their counters agree).
  std::function<void(double fraction)> progress{};
  // the batch lane the run's Taylor steppers get their series from
  // (simulate/series_batch.hpp): the same run, computed together with other
  // lanes' runs; none: alone
  SeriesLane* series_lane = nullptr;
};

// How a section run ended: its event loop's Termination (the same values in
// the same order), or, the loop complete, a record counted in events that
// max_periods did not fill.
enum class SectionTermination {
  completed, stopped_by_model, no_progress, frozen_time, non_finite_state, step_budget,
  integrator_failure, no_tangent_map,
  transient_impacts_not_reached,  // the transient's impacts (transient_impacts)
  crossings_not_reached,          // the crossings of a user-given section
  impacts_not_reached,            // the impacts of the impact section
};
static_assert(static_cast<int>(SectionTermination::no_tangent_map) ==
              static_cast<int>(Termination::no_tangent_map));

constexpr SectionTermination section_termination(Termination termination) {
  return static_cast<SectionTermination>(termination);
}

// The names poincare.json, sweep checkpoints and Python use (the event
// loop's own for its values).
constexpr std::string_view to_string(SectionTermination termination) {
  switch (termination) {
    case SectionTermination::transient_impacts_not_reached: return "transient_impacts_not_reached";
    case SectionTermination::crossings_not_reached: return "crossings_not_reached";
    case SectionTermination::impacts_not_reached: return "impacts_not_reached";
    default: return to_string(static_cast<Termination>(termination));
  }
}

// The termination named `text` (a sweep checkpoint's); none for another word.
constexpr std::optional<SectionTermination> parse_section_termination(std::string_view text) {
  for (int value = 0; value <= static_cast<int>(SectionTermination::impacts_not_reached); ++value)
    if (to_string(static_cast<SectionTermination>(value)) == text)
      return static_cast<SectionTermination>(value);
  return std::nullopt;
}

struct SectionResult {
  std::vector<SectionPoint> points;  // empty when they went to a point_sink
  std::uint64_t point_count = 0;     // points recorded, wherever they went
  std::optional<ContinuationState> final_state;  // none when the run stopped early
  SectionTermination termination = SectionTermination::completed;
  double omega = 0.0;              // forcing frequency (rad per time unit)
  double forcing_period = 0.0;     // 2π/ω
  double record_start = 0.0;       // time the recording began
  double transient_periods = 0.0;  // forcing periods the transient ran
  TransientEnd transient_end = TransientEnd::fixed;
  double periods_recorded = 0.0;   // forcing periods in the record window
  std::uint64_t impacts = 0;       // impacts in the record window
  std::uint64_t contact_phases = 0;  // contact phases begun or ended in the record window
  // the whole record window in one contact phase (at rest on a wall: no
  // contact phase begins or ends in it)
  bool rests_in_contact = false;
  std::uint64_t stick_impacts = 0;   // impacts in the record window whose impulse stuck
                                     // (EventRecord::sticks: the rigid model's friction)
  // the smallest |q̇| just before an impact in the record window (q per time
  // unit): how near the motion comes to grazing; NaN without impacts
  double min_impact_speed = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t steps = 0, rhs_evaluations = 0;  // over the whole run
  double lyapunov = std::numeric_limits<double>::quiet_NaN();  // largest exponent (1/time)
  std::string lyapunov_note;       // why it is NaN, where it is
  // λ1 … λN (1/time unit) when asked for: −∞ for a direction the contact
  // collapses; NaN where not computed (lyapunov_spectrum_note says why)
  std::vector<double> lyapunov_spectrum;
  std::vector<double> lyapunov_spectrum_error;  // half the range of the running estimate
                                                // over the last quarter of the periods
  std::string lyapunov_spectrum_note;
};

// Refuses (BadInput) a section run that cannot be sized: a forcing period
// 2π/ω that is not a finite positive time (key `omega`), or a transient and
// record that need more than `step_budget` steps at the least
// (periods × forcing period / max_step; key `transient` or `points`).
void check_section_size(const SectionRequest& request, double omega, double max_step,
                        std::uint64_t step_budget);

}  // namespace impactlab
