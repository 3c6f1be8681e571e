// Work-precision studies: cost (wall time, right-hand-side evaluations and
// steps per impact) against error (the largest error in impact times and
// impact velocities over the first N impacts) for each stepper and tolerance.
//
// References:
// * oscillators with a closed-form flow (linear_impact, bouncing_ball): the
//   impacts found by `closed_form_impacts`, a search of its own (a fine grid
//   of the exact flow that brackets sign changes and witness minima, refined
//   by TOMS 748) that shares nothing with the event loop but the system's
//   impact law;
// * the pendulum: the impacts of two independent high-order methods at their
//   tightest setting (GSL rk8pd and Boost.Odeint's Bulirsch–Stoer at rtol
//   1e-14); their spread is the reference's uncertainty, and only the leading
//   impacts where they agree to `trusted_time_spread` are compared (the
//   chattering case is sensitive to its accumulation decisions).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/math/tools/roots.hpp>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// One impact as the comparison sees it.
struct ImpactSample {
  double t = 0.0;            // impact time (s, or the oscillator's time unit)
  double qdot_before = 0.0;  // main coordinate's rate just before (rad/s, m/s, length/time)
};

// The impacts of a run (records of kind impact), in time order.
std::vector<ImpactSample> impacts_of(const std::vector<EventRecord>& events);

struct ReferenceImpacts {
  std::string method;                // "closed_form" or the methods compared
  std::vector<ImpactSample> impacts; // the trusted first N impacts
  double time_spread = 0.0;          // largest disagreement of the reference methods in t
  double velocity_spread = 0.0;      // and in qdot_before (0 for the closed form)
  std::size_t impacts_computed = 0;  // impacts the reference run produced before trimming
};

// Largest errors of `run` against the reference over the reference's impacts;
// a run with fewer impacts than the reference is compared over the ones it has
// and reports compared < reference size.
struct ImpactErrors {
  double time = 0.0;      // max |t − t_ref|
  double velocity = 0.0;  // max |q̇⁻ − q̇⁻_ref|
  std::size_t compared = 0;   // impacts compared
  std::size_t reference = 0;  // impacts in the reference
  [[nodiscard]] bool complete() const { return reference > 0 && compared == reference; }
};
ImpactErrors impact_errors(const ReferenceImpacts& reference, const std::vector<ImpactSample>& run);

namespace detail {

// Stops TOMS 748 when the bracket is a few ulps of t wide.
inline bool bracket_converged(double a, double b) {
  return std::fabs(b - a) <=
         4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(b));
}

}  // namespace detail

// The first `max_impacts` impacts of a system with a closed-form flow between
// t0 and t_end, found without the event loop: each witness of the current mode
// is sampled on a grid of max_step / grid_per_max_step along the exact flow
// from the last event; a sign change in the trigger direction brackets a root,
// and a witness minimum between two samples (the rate turning from falling to
// rising) is located by TOMS 748 on the rate and brackets the root before it
// when the minimum is at or below zero. TOMS 748 refines the earliest bracket
// to a few ulps, and the system's own transition (the impact law) restarts the
// flow. Only falling witnesses are supported (every mode of the exact-flow
// oscillators has only those).
template <class System>
  requires HasExactFlow<System>
std::vector<ImpactSample> closed_form_impacts(const System& system, typename System::State x0,
                                              typename System::Mode mode, double t0,
                                              double t_end, std::size_t max_impacts,
                                              int grid_per_max_step = 128) {
  using State = typename System::State;
  EventLog log(true);
  double t_start = t0;
  const double h = system.max_step() / grid_per_max_step;
  auto witness_at = [&](std::size_t k, double t) {
    State x;
    system.exact_flow(mode, x0, t_start, t, x);
    return system.witness(mode, k, x, t);
  };
  auto refine = [](auto&& f, double a, double b) {
    std::uintmax_t iterations = 200;
    const auto bracket =
        boost::math::tools::toms748_solve(f, a, b, detail::bracket_converged, iterations);
    return bracket.second;
  };

  while (log.count(EventKind::impact) < max_impacts && t_start < t_end) {
    double earliest = INFINITY;
    std::size_t earliest_witness = 0;
    for (std::size_t k = 0; k < system.witness_count(mode); ++k) {
      if (system.trigger_direction(mode, k) != TriggerDirection::falling)
        throw std::invalid_argument("closed_form_impacts: only falling witnesses are supported");
      double ta = t_start;
      WitnessSample wa = witness_at(k, ta);
      while (ta < std::min(t_end, earliest)) {
        const double tb = std::min(ta + h, t_end);
        const WitnessSample wb = witness_at(k, tb);
        auto value = [&](double t) { return witness_at(k, t).value; };
        double root = INFINITY;
        if (wa.value > 0.0 && wb.value <= 0.0) {
          root = wb.value == 0.0 ? tb : refine(value, ta, tb);
        } else if (wa.rate < 0.0 && wb.rate > 0.0 && wb.value > 0.0) {
          // a minimum inside: its value decides whether the witness dipped to zero
          auto rate = [&](double t) { return witness_at(k, t).rate; };
          const double t_min = refine(rate, ta, tb);
          const double at_min = value(t_min);
          if (at_min <= 0.0 && wa.value > 0.0)
            root = at_min == 0.0 ? t_min : refine(value, ta, t_min);
        }
        if (root < earliest) {
          earliest = root;
          earliest_witness = k;
          break;
        }
        ta = tb;
        wa = wb;
      }
    }
    if (!(earliest <= t_end)) break;
    State xe;
    system.exact_flow(mode, x0, t_start, earliest, xe);
    const auto transition =
        system.on_event(mode, earliest_witness, CrossingKind::crossing, xe, earliest, log);
    if (transition.stop) break;
    x0 = transition.state;
    mode = transition.mode;
    t_start = std::max(transition.time, earliest);
  }
  std::vector<ImpactSample> impacts = impacts_of(log.records());
  if (impacts.size() > max_impacts) impacts.resize(max_impacts);
  return impacts;
}

// The closed-form reference of a linear_impact or bouncing_ball scene, from
// t0 to t_end; std::invalid_argument for other oscillators.
ReferenceImpacts closed_form_reference(const Scene& scene, double t_end, std::size_t max_impacts);

// The reference of an oscillator without a closed form: the scene run with
// each of `methods` at rtol = 1e-14 (atol = 1e-16) from t0 to t_end; the
// impacts of the first method, trimmed to the leading ones where every method
// agrees within `trusted_time_spread` in time and the impact counts agree.
// The method "taylor_quad" is extended_precision_reference (below).
ReferenceImpacts integrated_reference(const Scene& scene, double t_end, std::size_t max_impacts,
                                      const std::vector<std::string>& methods,
                                      double trusted_time_spread);

// Whether the scene's oscillator has a closed-form flow (the `exact` stepper
// and closed_form_reference): linear_impact, bouncing_ball.
bool has_closed_form(const Scene& scene);

// The reference the bench measures errors against, from t0 to t_end: the
// closed form where there is one, else the scene integrated at rtol 1e-14 by
// two methods whose impacts are trusted where they agree within 1e-10: the
// quad-precision Taylor stepper and rk8pd for the pendulum's Model N (the
// CLI's bench cases), rk8pd and bulirsch_stoer otherwise.
ReferenceImpacts bench_reference(const Scene& scene, double t_end, std::size_t max_impacts);

// The impacts of a pendulum_walls scene (Model N) from t0 to t_end by the
// Taylor stepper in 113-bit arithmetic (Boost.Multiprecision's
// cpp_bin_float_quad) at rtol = atol = `tolerance` (1e-20: order 25): the
// series, the steps and the event polynomials in quad precision; the state
// is rounded to double only at events (the reset maps are the model's own),
// so the impact times are exact to about the double spacing of t.
std::vector<ImpactSample> extended_precision_reference(const Scene& scene, double t_end,
                                                       double tolerance = 1e-20);

// One stepper at one tolerance on one case.
struct WorkPrecisionPoint {
  std::string tool = "impactlab";  // impactlab or scipy
  std::string method;
  double rtol = 0.0, atol = 0.0;
  std::uint64_t impacts = 0;           // impacts of one timed run
  double seconds_per_impact = NAN;       // CPU s of the running thread per impact, median
                                        // over the repetitions (one core)
  double wall_seconds_per_impact = NAN;  // wall s per impact, median
  double rhs_per_impact = 0.0;         // right-hand-side evaluations per impact
  double steps_per_impact = 0.0;       // accepted steps per impact
  ImpactErrors errors;                 // against the case's reference
  double first_tenth_seconds_per_impact = NAN;  // CPU s per impact in the first tenth of
  double last_tenth_seconds_per_impact = NAN;   // simulated time and in the last tenth
  std::string termination;             // of the timed run
};

// Runs `scene` with the given method and tolerances for `periods` forcing
// periods, `repetitions` times; errors from the first run against `reference`.
WorkPrecisionPoint measure_point(const Scene& scene, const std::string& method, double rtol,
                                 double atol, double periods, int repetitions,
                                 const ReferenceImpacts& reference);

// The points no other point beats in both cost and impact-time error, by
// increasing error.
std::vector<WorkPrecisionPoint> pareto_front(const std::vector<WorkPrecisionPoint>& points);

// The cheapest point with impact-time error <= max_time_error (and every
// reference impact compared); nullptr if none.
const WorkPrecisionPoint* cheapest_within(const std::vector<WorkPrecisionPoint>& points,
                                          double max_time_error);

// Speed ratio at equal or better error: for each point of `slow`, its time per
// impact over that of the cheapest point of `fast` whose impact-time error is
// no larger. Points of `slow` that no point of `fast` matches are skipped.
struct SpeedRatio {
  double slow_error = 0.0;      // the slow tool's impact-time error at this point
  double fast_error = 0.0;      // the matched point's (<= slow_error)
  std::string slow_method, fast_method;
  double slow_rtol = 0.0, fast_rtol = 0.0;
  double ratio = 0.0;           // slow seconds per impact / fast seconds per impact
};
std::vector<SpeedRatio> speed_ratios(const std::vector<WorkPrecisionPoint>& slow,
                                     const std::vector<WorkPrecisionPoint>& fast);

}  // namespace impactlab
