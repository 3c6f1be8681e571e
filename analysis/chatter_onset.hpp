// The onset of complete chatter: where a chattering sequence of impacts on a
// wall stops accumulating before the push into the wall vanishes, and the
// mass escapes instead of coming to rest.
//
// Local model. Near the time t_r where the push on a mass at rest on the
// wall falls through zero, the normal acceleration towards the wall is
// c s (s = t_r − t, c > 0 its rate of fall). A hop that leaves the wall at
// time-to-go s with speed v lands after the time z s, where
//     z² − 3 z + 6 u = 0,   u = v / (c s²),
// and is returned with restitution r. In the scaled variable u the chatter
// is the map u ↦ r z (1/2 − z/3) / (1 − z)², with s ↦ (1 − z) s. It has one
// fixed point u* > 0 for every r in (0, 1), where
//     (3 − z*)(1 − z*)² = r (3 − 2 z*),
// a self-similar chatter whose remaining times shrink by ρ = 1 − z* per
// impact and whose accumulation point is t_r itself. The fixed point is
// unstable, with multiplier
//     μ = (3 − z*)² / ((1 − z*)(3 − 2 z*)²) > 1:
// a chatter that starts below its stable manifold drifts to u → 0 and
// accumulates before t_r (a contact phase follows), one above it escapes
// near t_r. The onset of complete chatter is where a chatter starts on the
// stable manifold, which is a regular condition: the ratio of successive
// remaining times q_k = s_{k+1}/s_k equals ρ up to O(s_k) on it, and departs
// from it like μ^k off it. Where the push vanishes the contact phase after
// the accumulation has zero length, but the landing push λ(t_l) is not a
// smooth function there (it grows like a fractional power of the distance to
// the onset), so the onset is not solved from λ(t_l) = 0.
//
// Margin. For the k-th impact of a run on one wall (k = 0 its first), with
// the first-order term in s eliminated between two successive ratios,
//     m_k = [(q_{k+1} − ρ) − (q_k − ρ) q_k] / μ^k,
// is zero on the manifold up to O(s_k²/μ^k), positive below it (complete),
// negative above it (escape), and of the size of the distance to the onset
// whatever k. The margin is taken at the real index K = ln(10⁴)/ln μ (the
// departure from the manifold amplified 10⁴ times, the O(s²) term reduced
// by ρ^{2K}), blended linearly between its two neighbouring integers so
// that it stays continuous when r changes; it needs K + 4 resolved impacts
// before t_r, and is NaN where the run has fewer.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include <impactlab/analysis/contact_landing.hpp>
#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/core/event_log.hpp>

namespace impactlab {

// The self-similar chatter of restitution r at a simple zero of the push.
struct SelfSimilarChatter {
  double hop_fraction = 0.0;     // z*: a hop's length over the time left to t_r
  double remaining_ratio = 0.0;  // ρ = 1 − z*
  double scaled_speed = 0.0;     // u* = v / (c s²) at each impact
  double multiplier = 0.0;       // μ, the scaled map's derivative at u*
  double index = 0.0;            // K = ln(10⁴) / ln μ, the impact the margin is taken at
};

// For r in (0, 1); nullopt outside.
std::optional<SelfSimilarChatter> self_similar_chatter(double restitution);

// One impact of a run on one wall: its time (s) and the ratio of its
// rebound to its approach speed, normal to the wall.
struct ChatterImpact {
  double t = 0.0;
  double restitution = 0.0;
};

struct ChatterMargin {
  double margin = std::numeric_limits<double>::quiet_NaN();  // at K; NaN: not enough impacts
  double spread = std::numeric_limits<double>::quiet_NaN();  // |m_{K0+1} − m_{K0}|
  std::vector<double> by_index;  // m_k for each k the run resolves (k + 2 before t_r)
  double index = std::numeric_limits<double>::quiet_NaN();   // K
  int side = 0;  // +1 the run accumulates (complete chatter), −1 it does not, 0 no chatter
};

// The margin of one run of impacts (in order, on one wall), `accumulated`
// where an accumulation follows it. push_at_rest(t) is the push into the
// wall on a mass resting on it at time t; t_r is its first zero after the
// run's first impact where it is positive, searched up to `horizon` (s),
// and the impacts before t_r are the chatter's. The run is a chatter where
// the push is positive at two of its impacts at least.
ChatterMargin chatter_run_margin(std::span<const ChatterImpact> run, bool accumulated,
                                 const std::function<double(double)>& push_at_rest,
                                 double horizon);

// A map evaluation at the section state x and the parameter p.
using OrbitAt = std::function<OrbitEvaluation(const OrbitPoint& x, double p)>;

struct ChatterOnset {
  bool found = false;
  OrbitPoint state;         // the flight from the release, on the section
  double parameter = 0.0;
  OrbitEvaluation orbit;    // the map evaluated there
  double error_estimate = 0.0;  // the last secant step and the margin's own error (p's unit)
};

// The onset of complete chatter in p near (x0, p0) and (x1, p1), two states
// on the section near the orbit: the root of the margin of the chatter that
// the flight from the release starts. That flight's state on the section,
// x_r(p), is the map's image wherever the chatter completes (the contact
// phase forgets the state) and is extrapolated linearly from the last two
// iterates where it does not: x_r and the margin are smooth across the
// onset, the map is not (its image past the onset departs from x_r like a
// fractional power of the distance), so no Newton on the orbit is solved
// there. The margin at index k is linear only close to its root (a
// departure from the manifold is amplified μ^k times by the k-th impact), so
// the root is refined index by index (k = 2, 4, …, then the margin at K), by
// secant steps in p at each.
ChatterOnset solve_chatter_onset(const OrbitAt& orbit_at, const OrbitPoint& x0, double p0,
                                 const OrbitPoint& x1, double p1);

// The runs of impacts among the records [begin, end) (consecutive impacts on
// one wall), each with its margin; the one nearest zero into
// the chatter_ fields of result (a run with a margin first, else the chatter
// that resolves the most indices). Systems with neither a landing push nor a
// stuck mode note nothing.
template <class System, class Records>
void note_chatter_margin(const System& system, Records begin, Records end, double horizon,
                         OrbitEvaluation& result) {
  if constexpr (HasLandingPush<System> || HasStuckMode<System>) {
    std::vector<ChatterImpact> run;
    auto consider = [&](Records first, Records last) {
      run.clear();
      for (auto event = first; event != last; ++event) {
        double restitution = 0.0;
        if constexpr (HasLandingPush<System>) {
          restitution = event->qdot_before == 0.0
                            ? 0.0
                            : std::fabs(event->qdot_after / event->qdot_before);
        } else {
          typename System::State before{}, after{};
          before[0] = after[0] = event->q;
          before[1] = event->qdot_before;
          after[1] = event->qdot_after;
          const double approach = system.witness(System::Mode::free, 0, before, event->t).rate;
          const double rebound = system.witness(System::Mode::free, 0, after, event->t).rate;
          restitution = approach == 0.0 ? 0.0 : std::fabs(rebound / approach);
        }
        run.push_back({event->t, restitution});
      }
      const EventRecord& wall_impact = *first;
      const bool accumulated = last != end && last->kind == EventKind::accumulation;
      const std::function<double(double)> push = [&system, &wall_impact](double t) {
        if constexpr (HasLandingPush<System>) {
          EventRecord at_rest = wall_impact;
          at_rest.kind = EventKind::accumulation;
          at_rest.t = t;
          return system.landing_push(at_rest).value_or(std::numeric_limits<double>::quiet_NaN());
        } else {
          typename System::State rest{};
          rest[0] = wall_impact.q;
          return system.witness(System::Mode::stuck, 0, rest, t).value;
        }
      };
      const ChatterMargin m = chatter_run_margin(run, accumulated, push, horizon);
      const bool has_margin = std::isfinite(m.margin);
      const bool had_margin = std::isfinite(result.chatter_margin);
      const bool longer = m.by_index.size() > result.chatter_margins.size();
      if ((has_margin && (!had_margin || std::fabs(m.margin) < std::fabs(result.chatter_margin))) ||
          (!has_margin && !had_margin && m.side != 0 && (result.chatter_side == 0 || longer))) {
        result.chatter_margin = m.margin;
        result.chatter_spread = m.spread;
        result.chatter_margins = m.by_index;
        result.chatter_index = m.index;
        result.chatter_side = m.side;
      }
    };
    auto first = begin;
    while (first != end) {
      if (first->kind != EventKind::impact) {
        ++first;
        continue;
      }
      auto last = first;
      while (last != end && last->kind == EventKind::impact && last->wall == first->wall) ++last;
      consider(first, last);
      first = last;
    }
  }
}

}  // namespace impactlab
