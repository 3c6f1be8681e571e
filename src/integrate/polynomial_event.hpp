// The first event of one witness on its Taylor polynomial over part of a
// step: the Taylor stepper's event location (integrate/taylor_stepper.hpp)
// for one oriented witness. It reads nothing of the system, so it is
// compiled once per number type (for double in polynomial_event.cpp), not
// once per system.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <impactlab/integrate/event_location.hpp>
#include <impactlab/integrate/polynomial_roots.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace impactlab {

// The first event of the oriented witness polynomial g (degree `order`, in
// h, the time past the step's start `t_start`) on [lo, hi]: a fall through
// zero from the armed side, or a minimum within the grazing tolerance;
// `one_sided`: a violation (below −tolerance without a crossing) is
// unresolved; `just_grazed`: the witness's grazing was the event at lo.
// The event's time is t_start + h rounded to double; `k` names the witness
// in the result; `lane`: the batch lane the stepper runs in, which refines
// the roots with other lanes' (integrate/series_lane.hpp), or none.
template <class Real>
LocatedEvent first_polynomial_event(const std::array<Real, taylor_max_order + 1>& g, int order,
                                    const Real& t_start, const Real& lo, const Real& hi,
                                    double tolerance, bool one_sided, bool just_grazed,
                                    std::size_t k, SeriesLane* lane) {
  using std::fabs;
  // monotone: |g'(h)| >= |g1| − Σ_{j≥2} j |g_j| h^{j−1} > 0 on [0, hi], so g
  // has no critical point there (sign_changes would find the same empty
  // set by re-expanding g' at the centre, at O(p²)): the step that leaves
  // a wall after an impact, whose witness starts at zero
  bool monotone = false;
  if (lo == 0) {
    Real slope_reach = 0, power = hi;  // power = hi^{j−1}
    for (int j = 2; j <= order; ++j) {
      slope_reach += j * fabs(g[j]) * power;
      power *= hi;
    }
    monotone = fabs(g[1]) > slope_reach;
  }
  const PolynomialRoots<taylor_max_order, Real> poly(g.data(), order, fabs(t_start), lane);
  auto at = [&](const Real& h) { return static_cast<double>(t_start + h); };
  const Real g_lo = poly.value(0, lo);
  const Real slope_lo = poly.value(1, lo);
  const bool leaving_zero = witness_at_zero(g_lo, slope_lo, t_start, tolerance) && slope_lo > 0;
  // g's monotone pieces [u, v], v the next critical point or hi, in
  // increasing order until one holds the event: the critical points past
  // it are not refined
  LocatedEvent first{};
  Real u = lo, gu = g_lo;  // the piece's start, and g there
  auto holds_the_event = [&](const Real& v) {
    const Real gv = poly.value(0, v);
    const bool falling = poly.value(1, (u + v) / 2) < 0;
    const bool armed = gu > 0 || (u == lo && leaving_zero);
    const bool interior_minimum = falling && v < hi;
    if (!armed) {
      if (one_sided && (gu < -tolerance || gv < -tolerance)) {
        first = {true, at(u), k, CrossingKind::unresolved};
        return true;
      }
    } else if (falling && !(u == lo && just_grazed && gv > -tolerance)) {
      if (gv <= 0.0) {
        // a dip below zero by less than the tolerance to a minimum inside
        // the step touches the wall: a grazing, as in event_location.hpp
        if (interior_minimum && gv > -tolerance && one_sided)
          first = {true, at(v), k, CrossingKind::grazing};
        else
          first = {true, std::min(at(poly.root(0, u, v, gu, gv, true)), at(hi)), k,
                   CrossingKind::crossing};
        return true;
      }
      if (interior_minimum && gv <= tolerance && one_sided) {
        first = {true, at(v), k, CrossingKind::grazing};
        return true;
      }
    }
    u = v;
    gu = gv;
    return false;
  };
  const bool found = !monotone && poly.visit_sign_changes(1, lo, hi, holds_the_event);
  if (!found) holds_the_event(hi);
  return first;
}

extern template LocatedEvent first_polynomial_event<double>(
    const std::array<double, taylor_max_order + 1>&, int, const double&, const double&,
    const double&, double, bool, bool, std::size_t, SeriesLane*);

}  // namespace impactlab
