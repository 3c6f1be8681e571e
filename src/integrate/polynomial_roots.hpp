// Rigorous isolation of the sign changes of a polynomial (a Taylor step's
// witness polynomial) on an interval, and of its derivatives.
//
// The m-th derivative P⁽ᵐ⁾ on [lo, hi], with centre c and radius r, is
// re-expanded at c (e_j = P⁽ᵐ⁺ʲ⁾(c) / j!). Then
// * |e_0| > Σ_{j≥1} |e_j| r^j: P⁽ᵐ⁾ has no zero on the interval;
// * |e_1| > Σ_{j≥2} j |e_j| r^{j−1}: P⁽ᵐ⁺¹⁾ has none, P⁽ᵐ⁾ is monotone and has
//   a root exactly where its end values differ in sign (safeguarded Newton
//   finds it: integrate/monotone_root.hpp);
// * otherwise the sign changes of P⁽ᵐ⁺¹⁾ split the interval into pieces on
//   which P⁽ᵐ⁾ is monotone. The recursion ends: P⁽ᵈᵉᵍʳᵉᵉ⁾ is a constant.
// No sampling: a root pair closer than any sampling grid (a grazing dip) is
// separated by the critical point between its roots.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <type_traits>

#include <impactlab/integrate/monotone_root.hpp>
#include <impactlab/integrate/polynomial_at.hpp>
#include <impactlab/integrate/series_lane.hpp>

namespace impactlab {

// up to `capacity` sorted points in an interval
template <int capacity, class Real = double>
struct PointList {
  std::array<Real, capacity> points{};
  int count = 0;
  void push(const Real& v) {
    if (count < capacity) points[count++] = v;
  }
};

template <int max_degree, class Real = double>
class PolynomialRoots {
 public:
  static constexpr int capacity = max_degree + 2;
  using Points = PointList<capacity, Real>;

  // p: coefficients c_0..c_degree of P(h) = Σ c_j h^j; t_scale: the size of
  // the absolute time at h (s), for the root's stopping tolerance; lane: the
  // batch lane that refines the roots (integrate/series_lane.hpp), or none
  PolynomialRoots(const Real* p, int degree, const Real& t_scale, SeriesLane* lane = nullptr)
      : degree_(degree), t_scale_(t_scale), lane_(lane) {
    for (int j = 0; j <= degree; ++j) derivative_[0][j] = p[j];
  }

  // P⁽ᵐ⁾(h)
  [[nodiscard]] Real value(int m, const Real& h) const {
    if (m > degree_) return Real(0);
    differentiate(m);
    return polynomial_at(derivative_[m].data(), degree_ - m, h);
  }

  // The sign changes of P⁽ᵐ⁾ in (lo, hi), in increasing order.
  [[nodiscard]] Points sign_changes(int m, const Real& lo, const Real& hi) const {
    Points out;
    visit_sign_changes(m, lo, hi, [&out](const Real& point) {
      out.push(point);
      return false;
    });
    return out;
  }

  // The points of sign_changes(m, lo, hi), the same numbers, each handed
  // to `visit` as soon as it is refined, in increasing order; visit(point)
  // returns true to stop, and the points after it are not refined. Returns
  // whether `visit` stopped.
  template <class Visit>
  bool visit_sign_changes(int m, const Real& lo, const Real& hi, Visit&& visit) const {
    using std::fabs;
    if (m >= degree_ || !(hi > lo)) return false;  // a constant has none
    const int n = degree_ - m;
    differentiate(m);
    // re-expansion at the centre by repeated synthetic division (e_0..e_n
    // set, the rest never read)
    const Real centre = (lo + hi) / 2, radius = (hi - lo) / 2;
    std::array<Real, max_degree + 1> e;
    for (int j = 0; j <= n; ++j) e[j] = derivative_[m][j];
    for (int i = 0; i < n; ++i)
      for (int j = n - 1; j >= i; --j) e[j] += centre * e[j + 1];
    Real value_bound = 0, slope_bound = 0, power = 1;
    for (int j = 1; j <= n; ++j) {
      if (j >= 2) slope_bound += j * fabs(e[j]) * power;  // power = r^{j−1}
      power *= radius;
      value_bound += fabs(e[j]) * power;
    }
    if (fabs(e[0]) > value_bound) return false;
    if (fabs(e[1]) > slope_bound)
      return visit_root_if_sign_change(m, lo, hi, value(m, lo), value(m, hi), visit);
    const Points inner = sign_changes(m + 1, lo, hi);
    Real left = lo, f_left = value(m, lo);
    for (int i = 0; i <= inner.count; ++i) {
      const Real right = i < inner.count ? inner.points[i] : hi;
      const Real f_right = value(m, right);
      if (visit_root_if_sign_change(m, left, right, f_left, f_right, visit)) return true;
      left = right;
      f_left = f_right;
    }
    return false;
  }

  // The root of P⁽ᵐ⁾ in [lo, hi], where it is monotone and its end values
  // differ in sign, to a few ulps of the absolute time
  // (integrate/monotone_root.hpp); the end on P⁽ᵐ⁾(hi)'s side of the final
  // bracket when `towards_hi`. In a batch lane, refined together with the
  // other lanes' roots of the same round, to the same bits.
  [[nodiscard]] Real root(int m, const Real& lo, const Real& hi, bool towards_hi) const {
    return root(m, lo, hi, value(m, lo), value(m, hi), towards_hi);
  }

  // The same, given f_lo = value(m, lo) and f_hi = value(m, hi).
  [[nodiscard]] Real root(int m, const Real& lo, const Real& hi, const Real& f_lo, const Real& f_hi,
                          bool towards_hi) const {
    if (f_hi == 0) return hi;
    if (f_lo == 0) return lo;
    differentiate(m + 2);
    const MonotoneRootProblem<Real> problem{
        derivative_[m].data(), derivative_[m + 1].data(),
        derivative_[std::min(m + 2, max_degree)].data(),  // unread where m + 2 > the degree
        degree_ - m, lo, hi, f_lo, f_hi, t_scale_, towards_hi};
    if constexpr (std::is_same_v<Real, double> && max_degree <= taylor_max_order) {
      if (lane_ != nullptr) {
        RootRequest request;
        request.evaluate = &evaluate_root_requests;
        request.before_series = true;
        request.problem = problem;
        lane_->compute(request);
        return request.root;
      }
    }
    return refine_monotone_root(problem);
  }

 private:
  // visit(the root of P⁽ᵐ⁾ in [lo, hi]) where its end values f_lo, f_hi
  // differ in sign; false (not stopped) where they do not
  template <class Visit>
  bool visit_root_if_sign_change(int m, const Real& lo, const Real& hi, const Real& f_lo,
                                 const Real& f_hi, Visit& visit) const {
    if ((f_lo < 0 && f_hi > 0) || (f_lo > 0 && f_hi < 0))
      return visit(root(m, lo, hi, f_lo, f_hi, false));
    return false;
  }

  // derivative m's coefficients, d_m[j] = c_{j+m} (j+m)! / j!, computed
  // when first asked for (most steps that the exclusion test keeps need
  // only P, P' and P'': the full table is degree² multiplications)
  void differentiate(int m) const {
    const auto degree = static_cast<std::size_t>(std::clamp(degree_, 0, max_degree));
    const auto last = std::min(static_cast<std::size_t>(std::max(m, 0)), degree);
    for (; ready_ < last; ++ready_)
      for (std::size_t j = 0; j + ready_ < degree; ++j)
        derivative_[ready_ + 1][j] = derivative_[ready_][j + 1] * static_cast<int>(j + 1);
  }

  // rows 0..ready_ filled up to the degree (no zero-initialisation: the
  // object is made once per witness in every step that the exclusion test
  // keeps); a cache of the polynomial's derivatives, hence mutable
  mutable std::array<std::array<Real, max_degree + 1>, max_degree + 1> derivative_;
  mutable std::size_t ready_ = 0;
  int degree_;
  Real t_scale_;
  SeriesLane* lane_;
};

}  // namespace impactlab
