// Event location on the dense output of one step.
//
// Each witness of the current mode is sampled, with its time derivative, at
// equally spaced times across the step. The sub-intervals are no longer than
// the system's max_step / samples_per_max_step (a system's max_step states
// the time scale on which its witnesses turn), so a short step of a
// low-order method is scanned at its ends only and a long step of a
// high-order method is subdivided. Between two samples:
// * a sign change in the trigger direction brackets a crossing;
// * a witness on the armed side at both samples whose rate turns from
//   towards zero to away from it has an extremum between them, located as a
//   root of the rate: past zero there, the crossing before it is bracketed;
//   touching zero within the grazing tolerance, the event is a grazing. This
//   is what keeps a double root (a grazing contact) inside one step from
//   being missed;
// * a witness that leaves zero (just after its own event) makes a hop: its
//   landing is bracketed past the hop's maximum, also where the hop is much
//   shorter than the sub-interval and the state has gone past zero and back
//   before the next sample (searched from the hop's length under the
//   witness's acceleration at the start);
// * a witness past zero by more than the tolerance with no crossing before
//   it is reported as unresolved (the loop stops rather than let the state
//   through).
// Brackets are refined with Boost.Math's TOMS 748 to a few ulps in time,
// below the integrator's own accuracy. Steppers without a continuous
// extension scan on a cheap interpolant first and redo the scan on their own
// re-taken steps only where it shows one of these patterns.
//
// The scan itself is compiled once, in event_location.cpp: it reads the
// system's witnesses through StepWitnesses, one virtual call per witness
// value, and only the sampling of the states below is compiled per system.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/platform/function_ref.hpp>

namespace impactlab {

struct EventLocationOptions {
  int samples_per_max_step = 4;   // scan sub-intervals per system max_step
  double max_step = INFINITY;      // the system's max_step (s), set by the loop
  double grazing_tolerance = 1e-12;  // |witness| at an extremum counted as touching
};

// Whether a witness with value `value` and rate `rate` at time t sits at a
// zero: within the grazing tolerance, or within 16 ulps of time of one
// (|value| <= 16 ε |t| |rate|). The second is the round-off of the event
// time itself: an event is located to a few ulps of t, and the step after it
// evaluates the witness afresh at that rounded time, so a witness whose rate
// is large (a slip V0 sin ωt through its zero, 29 m/s² on jin2003 at
// V0 = 4.163) starts up to |rate| ulp(t) from zero, on either side, more
// than an absolute tolerance of 1e-14 allows; taken for a new crossing, it
// would be found again a few ulps later.
template <class Real>
bool witness_at_zero(const Real& value, const Real& rate, const Real& t, double tolerance) {
  using std::fabs;
  return fabs(value) <= tolerance ||
         fabs(value) <= 16 * std::numeric_limits<double>::epsilon() * fabs(t) * fabs(rate);
}

struct LocatedEvent {
  bool found = false;
  double t = 0.0;
  std::size_t witness = 0;
  CrossingKind kind = CrossingKind::crossing;
};

// The scan's sample times across one step: times[0] = ta, times[n] = tb, and
// n equal sub-intervals between, at most max_intervals of them.
struct ScanSamples {
  static constexpr int max_intervals = 16;
  int n = 1;
  std::array<double, max_intervals + 1> times;

  ScanSamples(double ta, double tb, const EventLocationOptions& options);
};

// The witnesses of one mode over one step, as the scan reads them.
class StepWitnesses {
 public:
  [[nodiscard]] virtual std::size_t count() const = 0;
  [[nodiscard]] virtual TriggerDirection direction(std::size_t k) const = 0;
  // witness k on the state of the scan's sample i (0 ≤ i ≤ n)
  [[nodiscard]] virtual WitnessSample on_sample(std::size_t k, int i) const = 0;
  // witness k on the stepper's dense output at t
  [[nodiscard]] virtual WitnessSample on_state_at(std::size_t k, double t) const = 0;
  // witness k on the stepper's cheap interpolant at t (the scan's samples)
  [[nodiscard]] virtual WitnessSample on_scan_at(std::size_t k, double t) const = 0;

 protected:
  ~StepWitnesses() = default;
};

// The earliest event among the witnesses, on the samples of the step (see
// the header comment and the template below).
LocatedEvent locate_first_event(const StepWitnesses& witnesses, const ScanSamples& samples,
                                bool cheap_scan, const EventLocationOptions& options,
                                std::size_t just_grazed);

// Finds the earliest event of `mode` in [ta, tb]. `state_at(t, x)` is the
// stepper's dense output; `scan_at(t, x)` a cheaper interpolant for the
// scan's interior samples (`cheap_scan`; for most steppers scan_at is
// state_at and cheap_scan is false). Witnesses whose value at ta is not on the armed side
// (just after an event, or resting on a wall) are only armed once they leave.
// `just_grazed` names a witness whose grazing was the event at ta: the state
// there may still be closing on zero by the integrator's error, and the same
// minimum must not be found again in the first sub-interval.
// The two are views (platform/function_ref.hpp), so that this is compiled once
// per system, not once per stepper.
template <HybridSystem System>
LocatedEvent locate_first_event(const System& system, typename System::Mode mode, double ta,
                                double tb, const typename System::State& x_start,
                                const typename System::State& x_end,
                                FunctionRef<void(double, typename System::State&)> state_at,
                                FunctionRef<void(double, typename System::State&)> scan_at,
                                bool cheap_scan,
                                const EventLocationOptions& options,
                                std::size_t just_grazed = static_cast<std::size_t>(-1)) {
  using State = typename System::State;
  using Mode = typename System::Mode;
  const ScanSamples samples(ta, tb, options);

  // states at the sample times, shared by every witness
  // filled up to n below (no zero-initialisation: this runs once per step)
  std::array<State, ScanSamples::max_intervals + 1> states;
  for (int i = 0; i <= samples.n; ++i) {
    if (i == 0)
      states[i] = x_start;
    else if (i == samples.n)
      states[i] = x_end;
    else
      scan_at(samples.times[i], states[i]);
  }

  class Witnesses final : public StepWitnesses {
   public:
    Witnesses(const System& system, Mode mode, const ScanSamples& samples,
              const std::array<State, ScanSamples::max_intervals + 1>& states,
              FunctionRef<void(double, State&)> state_at, FunctionRef<void(double, State&)> scan_at)
        : system_(system),
          mode_(mode),
          samples_(samples),
          states_(states),
          state_at_(state_at),
          scan_at_(scan_at) {}

    [[nodiscard]] std::size_t count() const override { return system_.witness_count(mode_); }
    [[nodiscard]] TriggerDirection direction(std::size_t k) const override {
      return system_.trigger_direction(mode_, k);
    }
    [[nodiscard]] WitnessSample on_sample(std::size_t k, int i) const override {
      return system_.witness(mode_, k, states_[i], samples_.times[i]);
    }
    [[nodiscard]] WitnessSample on_state_at(std::size_t k, double t) const override {
      State x;
      state_at_(t, x);
      return system_.witness(mode_, k, x, t);
    }
    [[nodiscard]] WitnessSample on_scan_at(std::size_t k, double t) const override {
      State x;
      scan_at_(t, x);
      return system_.witness(mode_, k, x, t);
    }

   private:
    const System& system_;
    Mode mode_;
    const ScanSamples& samples_;
    const std::array<State, ScanSamples::max_intervals + 1>& states_;
    FunctionRef<void(double, State&)> state_at_;
    FunctionRef<void(double, State&)> scan_at_;
  };
  const Witnesses witnesses(system, mode, samples, states, state_at, scan_at);
  return locate_first_event(witnesses, samples, cheap_scan, options, just_grazed);
}

}  // namespace impactlab
