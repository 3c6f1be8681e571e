// The scan of integrate/event_location.hpp, compiled once for every system.
#include <impactlab/integrate/event_location.hpp>

#include <algorithm>
#include <cstdint>

#include <boost/math/tools/roots.hpp>

namespace impactlab {

namespace {

// The witness as seen by a falling trigger: a rising trigger is the falling
// trigger of the negated witness.
WitnessSample oriented(WitnessSample w, TriggerDirection direction, double sign_of_either) {
  const double s = direction == TriggerDirection::rising ? -1.0
                   : direction == TriggerDirection::either ? sign_of_either
                                                           : 1.0;
  return {s * w.value, s * w.rate};
}

// Full-precision bracketing: stop when the bracket is a few ulps wide.
struct TimeTolerance {
  bool operator()(double a, double b) const {
    return std::fabs(b - a) <= 4.0 * std::numeric_limits<double>::epsilon() *
                                   std::max(std::fabs(a), std::fabs(b));
  }
};

// Root of f on [a, b] with f(a) > 0 >= f(b) (or the reverse), by TOMS 748.
double bracketed_root(FunctionRef<double(double)> f, double a, double b, double fa, double fb) {
  if (fb == 0.0) return b;
  if (fa == 0.0) return a;
  // a bracket with no double inside (a time so large that its spacing is the
  // step, t0 = 1e15 s): the event is at its triggered end, to time resolution
  if (!(a < b) || std::nextafter(a, b) == b) return b;
  std::uintmax_t max_iterations = 100;
  const auto bracket = boost::math::tools::toms748_solve(f, a, b, fa, fb, TimeTolerance{},
                                                         max_iterations);
  // the endpoint on the triggered side: the event has happened there
  const double f_second = f(bracket.second);
  return (f_second <= 0.0) == (fb <= 0.0) ? bracket.second : bracket.first;
}

}  // namespace

ScanSamples::ScanSamples(double ta, double tb, const EventLocationOptions& options) {
  const double longest = options.max_step / std::max(options.samples_per_max_step, 1);
  n = std::isfinite(longest) ? static_cast<int>(std::clamp(std::ceil((tb - ta) / longest), 1.0,
                                                           static_cast<double>(max_intervals)))
                             : max_intervals;
  for (int i = 0; i <= n; ++i)
    times[i] = i == n ? tb : ta + (tb - ta) * static_cast<double>(i) / n;
}

LocatedEvent locate_first_event(const StepWitnesses& witnesses, const ScanSamples& samples,
                                bool cheap_scan, const EventLocationOptions& options,
                                std::size_t just_grazed) {
  const int n = samples.n;
  const auto& times = samples.times;
  const std::size_t witness_count = witnesses.count();

  LocatedEvent best;
  for (std::size_t k = 0; k < witness_count; ++k) {
    const TriggerDirection direction = witnesses.direction(k);
    const WitnessSample first = witnesses.on_sample(k, 0);
    // an `either` witness is oriented so that its starting side is the armed
    // one; starting at zero (just after its own event) the side it moves to is
    const double start_side =
        witness_at_zero(first.value, first.rate, times[0], options.grazing_tolerance)
            ? first.rate
            : first.value;
    const double either_sign = start_side >= 0.0 ? 1.0 : -1.0;
    auto sample = [&](int i) { return oriented(witnesses.on_sample(k, i), direction, either_sign); };
    auto witness_at = [&](double t) {
      return oriented(witnesses.on_state_at(k, t), direction, either_sign);
    };
    auto value_at = [&](double t) { return witness_at(t).value; };
    auto rate_at = [&](double t) { return witness_at(t).rate; };

    // A simple crossing in [tl, tr] (f(tl) > 0 >= f(tr) on state_at). With a
    // cheap scan the root of the interpolant is found first and Newton's
    // method on state_at (value and rate from one evaluation) finishes it;
    // TOMS 748 on state_at is the fallback, and the only method otherwise.
    auto crossing_root = [&](double tl, double tr, double fl, double fr) {
      if (cheap_scan) {
        auto scan_value = [&](double t) {
          return oriented(witnesses.on_scan_at(k, t), direction, either_sign).value;
        };
        const double hl = scan_value(tl), hr = scan_value(tr);
        double t = hl > 0.0 && hr <= 0.0 ? bracketed_root(scan_value, tl, tr, hl, hr)
                                         : 0.5 * (tl + tr);
        for (int iteration = 0; iteration < 6; ++iteration) {
          const WitnessSample w = witness_at(t);
          if (w.value == 0.0) return t;
          if (!(w.rate < 0.0)) break;
          const double next = t - w.value / w.rate;
          if (!(next >= tl && next <= tr)) break;
          // converged: keep the evaluated time (within a few ulps of next),
          // whose state the stepper still holds
          if (std::fabs(next - t) <= 4.0 * std::numeric_limits<double>::epsilon() * std::fabs(t))
            return t;
          t = next;
        }
      }
      return bracketed_root(value_at, tl, tr, fl, fr);
    };

    // The event pattern between two samples, if any, refined on state_at.
    // Its bracket ends must be samples of state_at itself: TOMS 748 needs a
    // sign change of the function it refines.
    auto classify = [&](int i, const WitnessSample& left,
                        const WitnessSample& right) -> LocatedEvent {
      const double tl = times[i], tr = times[i + 1];
      // a witness that starts at zero moving to its armed side (just after
      // its own event) and is back on the trigger side at the next sample has
      // made a hop: its maximum lies between, the crossing after that maximum
      const bool leaving_zero =
          i == 0 && witness_at_zero(left.value, left.rate, tl, options.grazing_tolerance) &&
          left.rate > 0.0;
      if (leaving_zero && direction != TriggerDirection::either) {
        double hi = tr;
        WitnessSample at_hi = right;
        if (right.value > 0.0) {
          // Back on the armed side at tr: a hop much shorter than the
          // interval (its length under the witness's acceleration at tl, a
          // difference of rates, within a quarter of it) may have landed
          // inside it, and the state gone past the wall and out again before
          // tr (a chatter near the time its wall stops attracting). Samples
          // from an eighth of that length on, each twice as far, to tr; the
          // first past zero ends the hop's bracket.
          const double offset = 1e-6 * (tr - tl);
          const double acceleration = (rate_at(tl + offset) - left.rate) / offset;
          if (!(acceleration < 0.0) || !(8.0 * left.rate / -acceleration < tr - tl)) return {};
          bool landed = false;
          for (double dt = 0.25 * left.rate / -acceleration; tl + dt < tr; dt *= 2.0) {
            at_hi = witness_at(tl + dt);
            if (at_hi.value <= 0.0) {
              hi = tl + dt;
              landed = true;
              break;
            }
          }
          if (!landed) return {};
        }
        // The right end `hi` is past zero. Falling there, the hop's maximum is
        // the root of the rate before it. Rising there, the witness also
        // turned back inside (tl, hi) (a chatter rebound whose wall stopped
        // attracting: the state went past the wall and out again), so the
        // interval is halved towards tl, keeping its right end past zero,
        // until the hop's falling flank is sampled, or a sample above zero
        // brackets the crossing after it.
        for (int halving = 0; halving <= 64; ++halving) {
          if (at_hi.rate < 0.0) {
            const double t_max = bracketed_root(rate_at, tl, hi, left.rate, at_hi.rate);
            const double v_max = value_at(t_max);
            if (v_max > 0.0)
              return {true, bracketed_root(value_at, t_max, hi, v_max, at_hi.value), k,
                      CrossingKind::crossing};
            return {};
          }
          const double mid = 0.5 * (tl + hi);
          if (!(mid > tl && mid < hi)) return {};
          const WitnessSample at_mid = witness_at(mid);
          if (at_mid.value > 0.0)
            return {true, bracketed_root(value_at, mid, hi, at_mid.value, at_hi.value), k,
                    CrossingKind::crossing};
          hi = mid;
          at_hi = at_mid;
        }
      } else if (leaving_zero && right.value <= 0.0) {
        return {};
      } else if (left.value > 0.0 && right.value <= 0.0) {
        return {true, crossing_root(tl, tr, left.value, right.value), k, CrossingKind::crossing};
      } else if (left.value > 0.0 && right.value > 0.0 && left.rate < 0.0 && right.rate > 0.0 &&
                 direction != TriggerDirection::either && !(i == 0 && k == just_grazed)) {
        // a minimum of the oriented witness lies inside (tl, tr)
        const double t_min = bracketed_root(
            [&](double t) { return -rate_at(t); }, tl, tr, -left.rate, -right.rate);
        const double v_min = value_at(t_min);
        if (v_min <= -options.grazing_tolerance)
          return {true, bracketed_root(value_at, tl, t_min, left.value, v_min), k,
                  CrossingKind::crossing};
        if (v_min <= options.grazing_tolerance) return {true, t_min, k, CrossingKind::grazing};
      }
      return {};
    };
    // a sample past zero by more than the tolerance, on the trigger side
    auto violated = [&](const WitnessSample& w) {
      return direction != TriggerDirection::either && w.value < -options.grazing_tolerance;
    };
    // whether a witness leaving zero at times[0] with rate `rate` may make a
    // hop that lands, goes past zero and comes back before times[1]: its
    // length under the acceleration there, 2 × rate / (−acceleration),
    // within a quarter of the interval (a longer hop lands in a later
    // interval, or stays past zero at times[1], where the scan sees it). The
    // acceleration is a difference of rates on the scan's dense output,
    // confirmed on state_at (a cheap scan's interpolant has the rate, not
    // the acceleration, of the flow).
    auto short_hop_possible = [&](double rate) {
      if (direction == TriggerDirection::either) return false;
      const double offset = 1e-6 * (times[1] - times[0]);
      const auto lands_inside = [&](double later_rate) {
        const double acceleration = (later_rate - rate) / offset;
        return acceleration < 0.0 && 8.0 * rate / -acceleration < times[1] - times[0];
      };
      const double later =
          oriented(witnesses.on_scan_at(k, times[0] + offset), direction, either_sign).rate;
      if (!lands_inside(later)) return false;
      return !cheap_scan || lands_inside(rate_at(times[0] + offset));
    };
    // whether two scan samples show one of classify's patterns (or a violation)
    auto classify_pattern = [&](int i, const WitnessSample& left, const WitnessSample& right) {
      if (violated(left) || violated(right)) return true;
      const bool leaving_zero =
          i == 0 && witness_at_zero(left.value, left.rate, times[0], options.grazing_tolerance) &&
          left.rate > 0.0;
      // leaving zero: a hop may land inside the interval even where the right
      // sample is back on the armed side (classify looks for it)
      if (leaving_zero) return right.value <= 0.0 || short_hop_possible(left.rate);
      if (!(left.value > 0.0)) return false;
      return right.value <= 0.0 || (left.rate < 0.0 && right.rate > 0.0 &&
                                    direction != TriggerDirection::either &&
                                    !(i == 0 && k == just_grazed));
    };
    // a sample of state_at (the scan's interior samples may come from scan_at)
    auto refined_sample = [&](int i) {
      if (i == 0 || i == n) return sample(i);
      return witness_at(times[i]);
    };
    // A cheap scan only decides whether this witness needs the accurate one:
    // where it shows any pattern, every sample of the step is taken again
    // from state_at and classified, so an interpolant's error can cost time
    // but never an event that the accurate samples show.
    bool needs_accurate_scan = !cheap_scan;
    if (cheap_scan) {
      WitnessSample left = sample(0);
      for (int i = 0; i < n && !needs_accurate_scan; ++i) {
        const WitnessSample right = sample(i + 1);
        needs_accurate_scan = classify_pattern(i, left, right);
        left = right;
      }
    }
    if (!needs_accurate_scan) continue;
    WitnessSample left = refined_sample(0);
    for (int i = 0; i < n; ++i) {
      const WitnessSample right = cheap_scan ? refined_sample(i + 1) : sample(i + 1);
      if (best.found && times[i] >= best.t) break;
      if (classify_pattern(i, left, right)) {
        LocatedEvent candidate = classify(i, left, right);
        // past zero without a crossing: the last sample still on the armed
        // side (or the step's start) is where the run can be trusted up to
        if (!candidate.found && (violated(left) || violated(right)))
          candidate = {true, times[i], k, CrossingKind::unresolved};
        if (candidate.found) {
          if (!best.found || candidate.t < best.t) best = candidate;
          break;
        }
      }
      left = right;
    }
  }
  return best;
}

}  // namespace impactlab
