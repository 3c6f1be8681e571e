// The root of a polynomial on an interval where it is monotone and its end
// values differ in sign: a Taylor step's event time, or a critical point
// that splits a witness polynomial into monotone pieces
// (integrate/polynomial_roots.hpp).
//
// Each step goes to the root nearest the iterate x of the polynomial's
// quadratic model there, d = −2 P / (P′ + sign(P′) √(P′² − 2 P P″)) (Euler's
// method: Newton's step −P/P′ where the model has no root), kept inside
// the bracket [a, b] of the sign change: each iterate replaces the end of
// its sign; an iterate outside the bracket, or a step not under half the
// step before the last, is replaced by the bracket's midpoint (the
// safeguard of Numerical Recipes' rtsafe). Newton's step alone would crawl
// where a step starts far out on a parabola (a chatter's crossing, just
// past the apex the bracket starts at: the steps halve, 10 to 17 of them
// on a 40 × 40 map's roots); the quadratic model lands there at once.
// Once the step is under half the tolerance, the next iterate goes past the
// model's root by half the tolerance, so that it lands beyond the root and
// closes the bracket from the other side (or halfway to the bracket's end,
// where that is nearer). The iteration ends when the bracket is within the
// tolerance, |b − a| ≤ 4 ε (s + |b|), s the size of the absolute time.
//
// It is written once over a number type V whose comparisons give masks:
// double (masks are bool), or LaneNumber (integrate/lane_number.hpp: masks
// are LaneMask), where each lane runs its own iteration in lockstep with the
// others and a lane whose bracket has closed keeps its values. A lane's
// iterates are then those of the same problem solved alone in double, to
// the last bit: the same IEEE operations in the same order (no
// FMA: the build is ISO C++20, -ffp-contract=off). So a batch lane that has
// its roots refined with other lanes' (integrate/series_lane.hpp) gets the
// scalar stepper's event times.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include <impactlab/integrate/polynomial_at.hpp>
#include <impactlab/integrate/series_lane.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace impactlab {

// the most steps a refinement takes: a cap above the about sixty steps that
// bisection alone needs to reach the tolerance from a step's length (the
// safeguard falls back on bisection wherever the model's steps stop halving)
inline constexpr int monotone_root_iterations = 100;

namespace detail {

// a where the mask holds, b where not (for double; LaneNumber's lane by
// lane: integrate/lane_number.hpp)
template <class Real>
Real select(bool mask, const Real& a, const Real& b) {
  return mask ? a : b;
}

inline bool any_lane(bool mask) { return mask; }

// The bracket [a, b] (f_a, f_b: P there, nonzero, of opposite signs)
// narrowed to the tolerance around P's root, as the header says; p: P's
// coefficients to `degree`, dp: P′'s to degree − 1, ddp: P″'s to
// degree − 2; scale: the size of the absolute time (s); `zero`, `half`,
// `four_epsilon`: those constants as V. Where an iterate hits P = 0
// exactly, a = b = that iterate.
template <class V>
void narrow_monotone_bracket(const V* p, const V* dp, const V* ddp, int degree, V& a, V& b,
                             const V& f_a, const V& f_b, const V& scale, const V& zero,
                             const V& half, const V& four_epsilon) {
  using std::fabs;
  using std::sqrt;
  auto size = [](const V& v) { return fabs(v); };
  auto tolerance_at = [&](const V& end) { return four_epsilon * (scale + size(end)); };
  auto closed = [&](const V& lo, const V& hi) { return size(hi - lo) <= tolerance_at(hi); };
  auto active = !closed(a, b);
  if (!any_lane(active)) return;
  // first iterate: where the chord through the ends crosses zero
  V fa = f_a;
  V x = a - fa * (b - a) / (f_b - fa);
  x = select((x > a) & (x < b), x, (a + b) * half);
  V step = b - a, step_before = b - a;
  for (int iteration = 0; iteration < monotone_root_iterations && any_lane(active); ++iteration) {
    const V fx = polynomial_at(p, degree, x);
    const V slope = polynomial_at(dp, degree - 1, x);
    const V curvature = polynomial_at(ddp, degree - 2, x);
    const auto hit = active & (fx == zero);
    const auto same_side = (fx > zero) == (fa > zero);
    const auto replaces_a = active & !hit & same_side;
    const auto replaces_b = active & !hit & !same_side;
    a = select(replaces_a | hit, x, a);
    fa = select(replaces_a, fx, fa);
    b = select(replaces_b | hit, x, b);
    active = active & !hit & !closed(a, b);
    // the quadratic model's root nearest x (x − model_step)
    const V twice_fx = fx + fx;
    const V discriminant = slope * slope - twice_fx * curvature;
    const auto model_has_root = discriminant > zero;
    const V root_of_discriminant = sqrt(select(model_has_root, discriminant, zero));
    const V denominator = slope + select(slope < zero, -root_of_discriminant, root_of_discriminant);
    const V model_step = select(model_has_root, twice_fx / denominator, fx / slope);
    const V model_root = x - model_step;
    // past the model's root by half the tolerance once its step is smaller
    // (halfway to the bracket's end where that end is nearer)
    const V margin = tolerance_at(x) * half;
    const V step_size = size(model_step);
    const auto converged = step_size <= margin;
    const V past_by_margin = select(model_step > zero, model_root - margin, model_root + margin);
    const V past_end = select(model_step > zero, (model_root + a) * half, (model_root + b) * half);
    const auto margin_inside = (past_by_margin > a) & (past_by_margin < b);
    const V past = select(margin_inside, past_by_margin, past_end);
    const V candidate = select(converged, past, model_root);
    const auto accepted = (candidate > a) & (candidate < b) &
                          (step_size + step_size <= size(step_before)) &
                          (candidate == candidate);
    const V next = select(accepted, candidate, (a + b) * half);
    step_before = select(active, step, step_before);
    step = select(active, next - x, step);
    x = select(active, next, x);
  }
}

}  // namespace detail

// One root problem: P(h) = Σ p_j h^j on [lo, hi], monotone there, with
// P(lo) = f_lo and P(hi) = f_hi nonzero and of opposite signs; dp, ddp: P′'s
// and P″'s coefficients (degree − 1, degree − 2; ddp unread below degree 2),
// each rounded as dp_j = p_{j+1} · (j + 1) and ddp_j = dp_{j+1} · (j + 1)
// in double (refine_monotone_roots derives them so from p in its lanes);
// t_scale: the size of the absolute time (s) for the tolerance. The
// answer: the bracket's end on f_hi's side where `towards_hi` (the event
// time at or just past the crossing), else the bracket's midpoint.
template <class Real>
struct MonotoneRootProblem {
  const Real* p = nullptr;
  const Real* dp = nullptr;
  const Real* ddp = nullptr;
  int degree = 0;
  Real lo{}, hi{}, f_lo{}, f_hi{};
  Real t_scale{};
  bool towards_hi = false;
};

// The root of one problem, in Real.
template <class Real>
Real refine_monotone_root(const MonotoneRootProblem<Real>& problem) {
  Real a = problem.lo, b = problem.hi;
  detail::narrow_monotone_bracket<Real>(problem.p, problem.dp, problem.ddp, problem.degree, a, b,
                                        problem.f_lo, problem.f_hi, problem.t_scale, Real(0),
                                        Real(0.5), Real(4 * std::numeric_limits<Real>::epsilon()));
  return problem.towards_hi ? b : (a + b) * Real(0.5);
}

// The roots of `count` problems of degree at most taylor_max_order, up to
// eight at a time in LaneNumber's lanes (AVX2 registers where the processor
// has them); each root is refine_monotone_root's for that problem alone, to
// the last bit.
void refine_monotone_roots(const MonotoneRootProblem<double>* const* problems, int count,
                           double* roots);

// A batch lane's request for one root (integrate/series_lane.hpp): the
// batch refines the roots that its lanes ask for in the same round together.
struct RootRequest : SeriesRequest {
  MonotoneRootProblem<double> problem;
  double root = 0.0;
};

// The evaluation of `count` RootRequests (SeriesRequest::evaluate).
void evaluate_root_requests(SeriesRequest* const* requests, int count);

}  // namespace impactlab
