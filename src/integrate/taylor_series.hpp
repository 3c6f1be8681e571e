// Truncated power series by automatic differentiation: the Taylor
// coefficients of the solution of x' = f(x, t) at t0, from the right-hand
// side written once over a number type.
//
// The right-hand side (and the witnesses) run once per order k = 0, 1, ...,
// p with TaylorVariable, a number whose value is its coefficient of order k
// and whose lower coefficients sit in a row of the evaluation's storage.
// Each arithmetic operation and elementary function computes its result's
// coefficient k by the classical recurrences (Cauchy product, the quotient
// rule, the coupled recurrence of sin and cos, those of exp, log, √ and
// a^α from e' = e a', a l' = a', s² = a, a p' = α a' p; Jorba & Zou 2005)
// and writes it to the row of its place in the sequence of operations, which
// is the same at every order; then the state's coefficient k + 1 = (coefficient k
// of f) / (k + 1). The compiler sees the whole right-hand side inlined at
// each order, so the newest coefficients pass from one operation to the next
// in registers and only the older ones are read from the rows (an earlier
// design recorded the operations on a tape and interpreted it: one
// evaluation of the pendulum at order 15 took 320 ns, this one 179 ns).
//
// Quantities that are polynomials of known degree in the time (the time
// itself, ωt) carry that degree: the sums of the recurrences stop there, and
// sin and cos of a linear argument cost O(1) per coefficient. The storage
// has a fixed number of rows and belongs to the caller, so nothing is
// allocated while stepping.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <type_traits>

#include <impactlab/core/fast_trig.hpp>
#include <impactlab/integrate/lane_number.hpp>

// GCC's per-function options that leave out partial redundancy elimination
// and code hoisting (TaylorSeries::evaluate_inlined_without_pre); other
// compilers have no such attribute and compile the function as the others
#if defined(__GNUC__) && !defined(__clang__)
#define IMPACTLAB_WITHOUT_PRE gnu::optimize("no-tree-pre", "no-code-hoisting")
#else
#define IMPACTLAB_WITHOUT_PRE
#endif

namespace impactlab {

// the highest order of a series (the Taylor stepper's orders stay below it)
inline constexpr int taylor_max_order = 32;

// 1 / k (1 <= k <= taylor_max_order + 1): a multiplication instead of a
// division on the order-by-order chain in double; exact division in the
// extended-precision types, whose 1/k a table of doubles would round
template <class Real>
Real taylor_reciprocal(int k) {
  if constexpr (std::is_same_v<Real, double> || is_lane_number<Real>) {
    static constexpr auto table = [] {
      std::array<double, taylor_max_order + 2> r{};
      for (int j = 1; j <= taylor_max_order + 1; ++j) r[j] = 1.0 / j;
      return r;
    }();
    return Real(table[k]);
  } else {
    return Real(1) / k;
  }
}

// A right-hand side with more operations than a series has rows: thrown from
// one place out of line, so that the series and tapes flattened into every
// system's loop carry a call instead of the exception's construction at each
// operation (a flows unit of the rigid pendulum: 18 % less code, 19 % less
// time to compile; docs/performance.md).
[[noreturn, gnu::cold, gnu::noinline]] inline void throw_too_many_operations() {
  throw std::length_error("taylor: the right-hand side has more operations than the series holds");
}

// The rows of one evaluation and the order in progress. Rows are taken in
// the order of the operations, from `first_free` on at every order.
template <class Real>
class TaylorEvaluation {
 public:
  static constexpr int stride = taylor_max_order + 1;  // coefficients 0..max order
  static constexpr int max_rows = 160;
  static constexpr int max_signs = 8;
  using Rows = std::array<Real, max_rows * stride>;

  TaylorEvaluation(Rows& rows, int first_free, const Real& t0, bool signs_from_slope)
      : rows_(rows.data()), first_free_(first_free), t0_(t0), signs_from_slope_(signs_from_slope) {}

  [[nodiscard]] int order() const { return order_; }
  [[nodiscard]] const Real& start_time() const { return t0_; }
  [[nodiscard]] bool signs_from_slope() const { return signs_from_slope_; }
  [[nodiscard]] Real* row(int r) const { return rows_ + r * stride; }

  void start_order(int k) {
    order_ = k;
    next_row_ = first_free_;
  }

  // the next operation's row
  Real* take_row() {
    if (next_row_ == max_rows) throw_too_many_operations();
    return row(next_row_++);
  }

  // the arguments of the sign functions (at order 0): see signs_need_slope
  void note_sign_argument(const Real* argument) {
    if (order_ == 0 && sign_count_ < max_signs) sign_arguments_[sign_count_++] = argument;
  }
  [[nodiscard]] int sign_count() const { return sign_count_; }
  [[nodiscard]] const Real* sign_argument(int i) const { return sign_arguments_[i]; }

 private:
  Real* rows_;
  int first_free_;
  Real t0_;
  bool signs_from_slope_;
  int order_ = 0;
  int next_row_ = 0;
  std::array<const Real*, max_signs> sign_arguments_{};
  int sign_count_ = 0;
};

// A number in a Taylor evaluation: a constant, or a series whose coefficient
// of the evaluation's current order is `value` and whose lower coefficients
// are in `row`.
template <class Real = double>
class TaylorVariable {
 public:
  static constexpr int unbounded = 1 << 20;  // the degree of a non-polynomial series

  TaylorVariable() = default;
  TaylorVariable(double constant) : value_(constant) {}  // NOLINT: constants mix in freely
  TaylorVariable(TaylorEvaluation<Real>* evaluation, Real* row, const Real& value, int degree,
                 const Real* rate = nullptr)
      : evaluation_(evaluation), row_(row), rate_(rate), value_(value), degree_(degree) {}

  // the result of an operation: `value` is its coefficient of the current
  // order, written to the operation's row
  static TaylorVariable result(TaylorEvaluation<Real>* evaluation, const Real& value, int degree) {
    Real* row = evaluation->take_row();
    row[evaluation->order()] = value;
    return {evaluation, row, value, std::min(degree, unbounded)};
  }

  [[nodiscard]] bool is_constant() const { return evaluation_ == nullptr; }
  // the constant's value (a constant only)
  [[nodiscard]] double constant() const { return constant_value(value_); }
  [[nodiscard]] TaylorEvaluation<Real>* evaluation() const { return evaluation_; }
  [[nodiscard]] Real* row() const { return row_; }
  // a state component's derivative coefficients: j · a_j = rate[j − 1]
  [[nodiscard]] const Real* rate() const { return rate_; }
  // the coefficient of the current order (a constant: the constant)
  [[nodiscard]] const Real& value() const { return value_; }
  [[nodiscard]] int degree() const { return degree_; }
  // the coefficient of order k of the series (k the current order or lower)
  [[nodiscard]] Real coefficient(int k) const {
    if (is_constant()) return k == 0 ? value_ : Real(0);
    return k == evaluation_->order() ? value_ : row_[k];
  }

 private:
  TaylorEvaluation<Real>* evaluation_ = nullptr;
  Real* row_ = nullptr;
  const Real* rate_ = nullptr;
  Real value_{};
  int degree_ = 0;
};

namespace detail {

template <class Real>
TaylorEvaluation<Real>* evaluation_of(const TaylorVariable<Real>& a, const TaylorVariable<Real>& b) {
  return a.is_constant() ? b.evaluation() : a.evaluation();
}

// c · a
template <class Real>
TaylorVariable<Real> scaled(const TaylorVariable<Real>& a, double c) {
  return TaylorVariable<Real>::result(a.evaluation(), c * a.value(), a.degree());
}

// a + c (the constant enters at order 0)
template <class Real>
TaylorVariable<Real> shifted(const TaylorVariable<Real>& a, double c) {
  const int k = a.evaluation()->order();
  return TaylorVariable<Real>::result(a.evaluation(), k == 0 ? Real(a.value() + c) : a.value(),
                                      a.degree());
}

template <class Real>
bool near_zero(const Real& a0, const Real& a1) {
  using std::fabs;
  return fabs(a0) <= 1e-9 * fabs(a1);
}

template <class Real>
Real sign_of(const Real& v) {
  return v > 0 ? Real(1) : v < 0 ? Real(-1) : Real(0);
}

// sin and cos of a constant, as doubles (the extended-precision types in
// their own precision first)
template <class Real>
std::array<double, 2> constant_sin_cos(const Real& v) {
  using std::cos;
  using std::sin;
  return {static_cast<double>(sin(v)), static_cast<double>(cos(v))};
}

// sin v and cos v in one call: for double, core/fast_trig.hpp's
// sin_cos_phase (one inline argument reduction for both, fdlibm's kernels;
// a few ulps, as the double right-hand sides' cos_phase); the library's
// functions for the extended-precision types
template <class Real>
void sin_and_cos(const Real& v, Real& s, Real& c) {
  using std::cos;
  using std::sin;
  if constexpr (std::is_same_v<Real, double>) {
    sin_cos_phase(v, s, c);
  } else {
    s = sin(v);
    c = cos(v);
  }
}

// The recurrences of orders k >= 1, shared by TaylorVariable (which passes
// its operands' newest coefficients as values, kept in registers) and the
// pass over lanes (integrate/series_tape.cpp, which reads them from the
// rows), so that both perform the same operations in the same order.

// coefficient k of a · b: x, y the rows, xk, yk the coefficients k, da, db
// the degrees; the products of older coefficients first, the newest
// (a_k b_0 and a_0 b_k) last, the sums stopping at the degrees
template <class Real>
Real product_coefficient(const Real* x, const Real* y, const Real& xk, const Real& yk, int k,
                         int da, int db) {
  Real sum = 0;
  for (int j = std::max(1, k - db); j <= std::min(k - 1, da); ++j) sum += x[j] * y[k - j];
  if (k <= db) sum += x[0] * yk;
  if (k <= da) sum += xk * y[0];
  return sum;
}

// coefficient k of q = a / b: b_0 q_k = a_k − Σ_{j=1..k} b_j q_{k−j} (y b's
// row, yk its coefficient k, db its degree; q the quotient's row)
template <class Real>
Real quotient_coefficient(const Real& ak, const Real* y, const Real& yk, const Real* q, int k,
                          int db) {
  Real sum = ak;
  for (int j = 1; j <= std::min(k - 1, db); ++j) sum -= y[j] * q[k - j];
  if (k <= db) sum -= yk * q[0];
  return sum / y[0];
}

// coefficients k of sin a and cos a (s, c their rows), by s' = c a',
// c' = −s a': k s_k = Σ_{j=1..k} j a_j c_{k−j}, k c_k = −Σ j a_j s_{k−j}.
// a = a0 + a1 h (ωt): k s_k = a1 c_{k−1}, k c_k = −a1 s_{k−1}
template <class Real>
void sine_of_linear(const Real& a1, const Real* s, const Real* c, int k, Real& sk, Real& ck) {
  sk = (a1 * c[k - 1]) * taylor_reciprocal<Real>(k);
  ck = -(a1 * s[k - 1]) * taylor_reciprocal<Real>(k);
}

// a a state component: j a_j = f_{j−1}, its derivative's coefficient, read,
// not computed; the newest terms last (j = 1: the previous order's c_{k−1},
// s_{k−1}; j = k: f_{k−1})
template <class Real>
void sine_of_state(const Real* f, const Real* s, const Real* c, int k, Real& sk, Real& ck) {
  Real s_sum = 0, c_sum = 0;
  for (int j = 2; j < k; ++j) {
    s_sum += f[j - 1] * c[k - j];
    c_sum += f[j - 1] * s[k - j];
  }
  if (k > 1) {
    s_sum += f[k - 1] * c[0];
    c_sum += f[k - 1] * s[0];
  }
  s_sum += f[0] * c[k - 1];
  c_sum += f[0] * s[k - 1];
  sk = s_sum * taylor_reciprocal<Real>(k);
  ck = -c_sum * taylor_reciprocal<Real>(k);
}

// any other a of degree `degree`: j a_j kept in a row of its own (ja, up to k)
template <class Real>
void sine_of_series(const Real* ja, int degree, const Real* s, const Real* c, int k, Real& sk,
                    Real& ck) {
  Real s_sum = 0, c_sum = 0;
  for (int j = 1; j <= std::min(k, degree); ++j) {
    s_sum += ja[j] * c[k - j];
    c_sum += ja[j] * s[k - j];
  }
  sk = s_sum * taylor_reciprocal<Real>(k);
  ck = -c_sum * taylor_reciprocal<Real>(k);
}

// coefficient k of e = exp a, by e' = e a': k e_k = Σ_{j=1..k} j a_j e_{k−j}
// (ja: j a_j, up to k; the sum stopping at a's degree)
template <class Real>
Real exp_coefficient(const Real* ja, int degree, const Real* e, int k) {
  Real sum = 0;
  for (int j = 1; j <= std::min(k, degree); ++j) sum += ja[j] * e[k - j];
  return sum * taylor_reciprocal<Real>(k);
}

// coefficient k of l = log a, by a l' = a': a_0 l_k = a_k − (1/k)
// Σ_{j=1..k−1} j l_j a_{k−j} (x a's row, up to k; l the logarithm's row)
template <class Real>
Real log_coefficient(const Real* x, int degree, const Real* l, int k) {
  Real sum = 0;
  for (int j = std::max(1, k - degree); j <= k - 1; ++j) sum += (Real(j) * l[j]) * x[k - j];
  return (x[k] - sum * taylor_reciprocal<Real>(k)) / x[0];
}

// coefficient k of s = √a, by s² = a: 2 s_0 s_k = a_k − Σ_{j=1..k−1} s_j s_{k−j}
template <class Real>
Real sqrt_coefficient(const Real& ak, const Real* s, int k) {
  Real sum = 0;
  for (int j = 1; j <= k - 1; ++j) sum += s[j] * s[k - j];
  return (ak - sum) / (Real(2) * s[0]);
}

// coefficient k of p = a^α (α a constant), by a p' = α a' p:
// k a_0 p_k = Σ_{j=0..k−1} (α (k − j) − j) a_{k−j} p_j (x a's row, up to k)
template <class Real>
Real power_coefficient(const Real& alpha, const Real* x, int degree, const Real* p, int k) {
  Real sum = 0;
  for (int j = std::max(0, k - degree); j <= k - 1; ++j)
    sum += ((alpha * Real(k - j) - Real(j)) * x[k - j]) * p[j];
  return sum * taylor_reciprocal<Real>(k) / x[0];
}

// sin a and cos a, computed together (two rows, and a third for j · a_j
// where a is neither a state component nor linear in t)
template <class Real>
std::array<TaylorVariable<Real>, 2> sin_cos(const TaylorVariable<Real>& a) {
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  Real* s = evaluation->take_row();
  Real* c = evaluation->take_row();
  Real* ja = a.degree() > 1 && a.rate() == nullptr ? evaluation->take_row() : nullptr;
  Real sk, ck;
  if (k == 0) {
    sin_and_cos(a.value(), sk, ck);
  } else if (a.degree() == 0) {  // a constant over the step (a sign, say)
    sk = 0;
    ck = 0;
  } else if (a.degree() == 1) {
    sine_of_linear(k == 1 ? a.value() : a.row()[1], s, c, k, sk, ck);
  } else if (a.rate() != nullptr) {
    sine_of_state(a.rate(), s, c, k, sk, ck);
  } else {
    ja[k] = k * a.value();
    sine_of_series(ja, a.degree(), s, c, k, sk, ck);
  }
  s[k] = sk;
  c[k] = ck;
  constexpr int unbounded = TaylorVariable<Real>::unbounded;
  return {TaylorVariable<Real>(evaluation, s, sk, unbounded),
          TaylorVariable<Real>(evaluation, c, ck, unbounded)};
}

}  // namespace detail

// The value where a series is expanded (its coefficient 0, at every order).
// A system whose definitions switch at known times (analysis/
// run_continuation.hpp's suppressed contact window) decides by it which
// definition a step uses, the step ending at each switch.
template <class Real>
double start_value(const TaylorVariable<Real>& v) {
  return static_cast<double>(v.coefficient(0));
}

// --- arithmetic: constants fold; a constant operand scales or shifts ---

template <class Real>
TaylorVariable<Real> operator+(const TaylorVariable<Real>& a, const TaylorVariable<Real>& b) {
  if (a.is_constant() && b.is_constant()) return constant_value(a.value() + b.value());
  if (b.is_constant()) return detail::shifted(a, constant_value(b.value()));
  if (a.is_constant()) return detail::shifted(b, constant_value(a.value()));
  return TaylorVariable<Real>::result(a.evaluation(), a.value() + b.value(),
                                      std::max(a.degree(), b.degree()));
}

template <class Real>
TaylorVariable<Real> operator-(const TaylorVariable<Real>& a) {
  if (a.is_constant()) return constant_value(-a.value());
  return TaylorVariable<Real>::result(a.evaluation(), -a.value(), a.degree());
}

template <class Real>
TaylorVariable<Real> operator-(const TaylorVariable<Real>& a, const TaylorVariable<Real>& b) {
  if (a.is_constant() && b.is_constant()) return constant_value(a.value() - b.value());
  if (b.is_constant()) return detail::shifted(a, constant_value(-b.value()));
  if (a.is_constant()) {
    const int k = b.evaluation()->order();
    return TaylorVariable<Real>::result(b.evaluation(),
                                        k == 0 ? Real(a.value() - b.value()) : Real(-b.value()),
                                        b.degree());
  }
  return TaylorVariable<Real>::result(a.evaluation(), a.value() - b.value(),
                                      std::max(a.degree(), b.degree()));
}

// coefficient k of a · b (detail::product_coefficient)
template <class Real>
TaylorVariable<Real> operator*(const TaylorVariable<Real>& a, const TaylorVariable<Real>& b) {
  if (a.is_constant() && b.is_constant()) return constant_value(a.value() * b.value());
  if (a.is_constant()) return detail::scaled(b, constant_value(a.value()));
  if (b.is_constant()) return detail::scaled(a, constant_value(b.value()));
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  const int degree = std::min(TaylorVariable<Real>::unbounded, a.degree() + b.degree());
  if (k == 0) return TaylorVariable<Real>::result(evaluation, a.value() * b.value(), degree);
  return TaylorVariable<Real>::result(
      evaluation,
      detail::product_coefficient(a.row(), b.row(), a.value(), b.value(), k, a.degree(), b.degree()),
      degree);
}

// q = a / b (detail::quotient_coefficient)
template <class Real>
TaylorVariable<Real> operator/(const TaylorVariable<Real>& a, const TaylorVariable<Real>& b) {
  if (b.is_constant()) return a * TaylorVariable<Real>(1.0 / constant_value(b.value()));
  TaylorEvaluation<Real>* evaluation = b.evaluation();
  const int k = evaluation->order();
  Real* q = evaluation->take_row();
  q[k] = k == 0 ? a.coefficient(0) / b.value()
                : detail::quotient_coefficient(a.coefficient(k), b.row(), b.value(), q, k,
                                               b.degree());
  const int degree = b.degree() == 0 ? a.degree() : TaylorVariable<Real>::unbounded;
  return {evaluation, q, q[k], degree};
}

template <class Real>
TaylorVariable<Real> operator+(const TaylorVariable<Real>& a, double b) { return a + TaylorVariable<Real>(b); }
template <class Real>
TaylorVariable<Real> operator+(double a, const TaylorVariable<Real>& b) { return TaylorVariable<Real>(a) + b; }
template <class Real>
TaylorVariable<Real> operator-(const TaylorVariable<Real>& a, double b) { return a - TaylorVariable<Real>(b); }
template <class Real>
TaylorVariable<Real> operator-(double a, const TaylorVariable<Real>& b) { return TaylorVariable<Real>(a) - b; }
template <class Real>
TaylorVariable<Real> operator*(const TaylorVariable<Real>& a, double b) { return a * TaylorVariable<Real>(b); }
template <class Real>
TaylorVariable<Real> operator*(double a, const TaylorVariable<Real>& b) { return TaylorVariable<Real>(a) * b; }
template <class Real>
TaylorVariable<Real> operator/(const TaylorVariable<Real>& a, double b) { return a / TaylorVariable<Real>(b); }
template <class Real>
TaylorVariable<Real> operator/(double a, const TaylorVariable<Real>& b) { return TaylorVariable<Real>(a) / b; }

template <class Real, class Other>
TaylorVariable<Real>& operator+=(TaylorVariable<Real>& a, const Other& b) { return a = a + b; }
template <class Real, class Other>
TaylorVariable<Real>& operator-=(TaylorVariable<Real>& a, const Other& b) { return a = a - b; }
template <class Real, class Other>
TaylorVariable<Real>& operator*=(TaylorVariable<Real>& a, const Other& b) { return a = a * b; }
template <class Real, class Other>
TaylorVariable<Real>& operator/=(TaylorVariable<Real>& a, const Other& b) { return a = a / b; }

// --- elementary functions, found by argument-dependent lookup from a
// right-hand side that calls them unqualified ---

template <class Real>
TaylorVariable<Real> sin(const TaylorVariable<Real>& a) {
  using std::sin;
  if (a.is_constant()) return detail::constant_sin_cos(a.value())[0];
  return detail::sin_cos(a)[0];
}

template <class Real>
TaylorVariable<Real> cos(const TaylorVariable<Real>& a) {
  using std::cos;
  if (a.is_constant()) return detail::constant_sin_cos(a.value())[1];
  return detail::sin_cos(a)[1];
}

// sin a and cos a from one run of the coupled recurrence (sin(a) and cos(a)
// run it each: a caller that needs both, as the chain rule of a dual number
// does, calls this; integrate/dual_number.hpp)
template <class Real>
SineAndCosine<TaylorVariable<Real>> sin_and_cos_of(const TaylorVariable<Real>& a) {
  using std::cos;
  using std::sin;
  if (a.is_constant())
    return {detail::constant_sin_cos(a.value())[0], detail::constant_sin_cos(a.value())[1]};
  const std::array<TaylorVariable<Real>, 2> pair = detail::sin_cos(a);
  return {pair[0], pair[1]};
}

namespace detail {

// the degree of exp, log, √ or a power of a series of degree `degree`:
// constant over the step where the argument is, not a polynomial otherwise
constexpr int function_degree(int degree) {
  return degree == 0 ? 0 : TaylorVariable<double>::unbounded;
}

}  // namespace detail

// exp a (a second row for j a_j), log a, √a and a^α for a constant α: the
// recurrences above; a quantity constant over the step (degree 0) gives one
template <class Real>
TaylorVariable<Real> exp(const TaylorVariable<Real>& a) {
  using std::exp;
  if (a.is_constant()) return constant_value(Real(exp(a.value())));
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  Real* e = evaluation->take_row();
  Real* ja = evaluation->take_row();
  if (k == 0) {
    e[0] = exp(a.value());
  } else {
    ja[k] = Real(k) * a.value();
    e[k] = detail::exp_coefficient(ja, a.degree(), e, k);
  }
  return {evaluation, e, e[k], detail::function_degree(a.degree())};
}

template <class Real>
TaylorVariable<Real> log(const TaylorVariable<Real>& a) {
  using std::log;
  if (a.is_constant()) return constant_value(Real(log(a.value())));
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  Real* l = evaluation->take_row();
  l[k] = k == 0 ? Real(log(a.value())) : detail::log_coefficient(a.row(), a.degree(), l, k);
  return {evaluation, l, l[k], detail::function_degree(a.degree())};
}

template <class Real>
TaylorVariable<Real> sqrt(const TaylorVariable<Real>& a) {
  using std::sqrt;
  if (a.is_constant()) return constant_value(Real(sqrt(a.value())));
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  Real* r = evaluation->take_row();
  r[k] = k == 0 ? Real(sqrt(a.value())) : detail::sqrt_coefficient(a.value(), r, k);
  return {evaluation, r, r[k], detail::function_degree(a.degree())};
}

template <class Real>
TaylorVariable<Real> pow(const TaylorVariable<Real>& a, double alpha) {
  using std::pow;
  if (a.is_constant()) return constant_value(Real(pow(a.value(), Real(alpha))));
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  Real* p = evaluation->take_row();
  p[k] = k == 0 ? Real(pow(a.value(), Real(alpha)))
                : detail::power_coefficient(Real(alpha), a.row(), a.degree(), p, k);
  return {evaluation, p, p[k], detail::function_degree(a.degree())};
}

// core/fast_trig.hpp's names: the same functions on a series
template <class Real>
TaylorVariable<Real> sin_angle(const TaylorVariable<Real>& a) { return sin(a); }
template <class Real>
TaylorVariable<Real> cos_phase(const TaylorVariable<Real>& a) { return cos(a); }
template <class Real>
TaylorVariable<Real> sin_phase(const TaylorVariable<Real>& a) { return sin(a); }

// The sign of a (−1, 0, +1), constant over a step: the systems end a step at
// every zero of a quantity whose sign they use (slip reversals are events).
// With the evaluation's signs_from_slope, an argument that starts within
// round-off of a zero (|a0| <= 1e-9 s · |a1|) takes the sign of a1, the side
// it moves to, from the previous evaluation at the same point (its row still
// holds a1 while order 0 is computed; see signs_need_slope).
template <class Real>
TaylorVariable<Real> sign(const TaylorVariable<Real>& a) {
  if (a.is_constant()) return constant_value(detail::sign_of(a.value()));
  TaylorEvaluation<Real>* evaluation = a.evaluation();
  const int k = evaluation->order();
  evaluation->note_sign_argument(a.row());
  Real s = 0;
  if (k == 0) {
    s = evaluation->signs_from_slope() && detail::near_zero(a.value(), a.row()[1])
            ? detail::sign_of(a.row()[1])
            : detail::sign_of(a.value());
  }
  return TaylorVariable<Real>::result(evaluation, s, 0);
}

template <class Real>
TaylorVariable<Real> fabs(const TaylorVariable<Real>& a) { return sign(a) * a; }

// Whether a sign of the last evaluation sits at a zero of its argument that
// the argument is leaving for the other side (just after a slip reversal):
// evaluate again with signs_from_slope.
template <class Real>
bool signs_need_slope(const TaylorEvaluation<Real>& evaluation) {
  for (int i = 0; i < evaluation.sign_count(); ++i) {
    const Real* a = evaluation.sign_argument(i);
    if (detail::near_zero(a[0], a[1]) && detail::sign_of(a[1]) != detail::sign_of(a[0])) return true;
  }
  return false;
}

// The Taylor coefficients 0..order at (t0, x0) of x' = f(x, t) and of up to
// max_outputs further functions of (x, t) (the witnesses). `rhs(x, t, dxdt,
// outputs)` runs the right-hand side over TaylorVariable<Real> and returns
// how many outputs it set; it must perform the same operations at every
// order. Rows: 0..N−1 the state, N..2N−1 the state's derivatives, 2N the
// time, then the operations'.
template <class Real, std::size_t N>
class TaylorSeries {
 public:
  static constexpr int max_outputs = 8;
  using Evaluation = TaylorEvaluation<Real>;
  using Variables = std::array<TaylorVariable<Real>, N>;
  using Outputs = std::array<TaylorVariable<Real>, max_outputs>;

  template <class Rhs>
  void evaluate(const Real* x0, const Real& t0, int order, Rhs&& rhs, bool signs_from_slope = false) {
    if constexpr (std::is_same_v<Real, double> && N > most_states_with_pre) {
      evaluate_inlined_without_pre(x0, t0, order, rhs, signs_from_slope);
    } else if constexpr (std::is_same_v<Real, double>) {
      evaluate_inlined(x0, t0, order, rhs, signs_from_slope);
    } else {
      evaluate_orders(x0, t0, order, rhs, signs_from_slope);
    }
  }

  [[nodiscard]] const Real* state(std::size_t i) const { return &rows_[i * Evaluation::stride]; }
  [[nodiscard]] const Real* output(int j) const { return output_rows_[j]; }
  [[nodiscard]] int output_count() const { return output_count_; }
  // see signs_need_slope
  [[nodiscard]] bool needs_slope() const { return needs_slope_; }

 private:
  // In double, the right-hand side and every operation inlined into the
  // loop over the orders, whatever the inliner's size limits (flatten): that
  // is where the speed of this design comes from. Not for the
  // extended-precision types, whose arithmetic inlined whole would take the
  // compiler tens of gigabytes.
  template <class Rhs>
  [[gnu::flatten]] void evaluate_inlined(const Real* x0, const Real& t0, int order, Rhs& rhs,
                                         bool signs_from_slope) {
    evaluate_orders(x0, t0, order, rhs, signs_from_slope);
  }

  // The same with more than eight states (the variational equations), but
  // without GCC's partial redundancy elimination and code hoisting: over
  // the loop whose body is such a system's whole right-hand side, those two
  // passes took about half of the compile time of its flows' unit, the
  // longest of the build (docs/performance.md, "The tangent series compiled
  // without partial redundancy elimination"). An attribute, not the unit's
  // flags: those of the precompiled headers would override them.
  static constexpr std::size_t most_states_with_pre = 8;
  template <class Rhs>
  [[gnu::flatten, IMPACTLAB_WITHOUT_PRE]] void evaluate_inlined_without_pre(
      const Real* x0, const Real& t0, int order, Rhs& rhs, bool signs_from_slope) {
    evaluate_orders(x0, t0, order, rhs, signs_from_slope);
  }

  // One evaluation in progress: its rows' bookkeeping and the variables of
  // the order being computed.
  struct Pass {
    Pass(TaylorSeries& series, const Real* x0, const Real& t0, bool signs_from_slope)
        : evaluation(series.rows_, 2 * N + 1, t0, signs_from_slope) {
      for (std::size_t i = 0; i < N; ++i) series.state_row(i)[0] = x0[i];
    }
    Evaluation evaluation;
    Variables x, dxdt;
    Outputs outputs;
  };

  template <class Rhs>
  void evaluate_orders(const Real* x0, const Real& t0, int order, Rhs& rhs, bool signs_from_slope) {
    Pass pass(*this, x0, t0, signs_from_slope);
    for (int k = 0; k <= order; ++k) evaluate_order(pass, k, order, rhs);
    needs_slope_ = signs_need_slope(pass.evaluation);
  }

  // coefficient k of every operation, and the state's coefficient k + 1
  template <class Rhs>
  void evaluate_order(Pass& pass, int k, int order, Rhs& rhs) {
    static_assert(2 * N + 1 < Evaluation::max_rows);
    Evaluation& evaluation = pass.evaluation;
    Real* time = row(2 * N);
    evaluation.start_order(k);
    for (std::size_t i = 0; i < N; ++i)
      pass.x[i] = TaylorVariable<Real>(&evaluation, state_row(i), state_row(i)[k],
                                       TaylorVariable<Real>::unbounded, rate_row(i));
    time[k] = k == 0 ? evaluation.start_time() : k == 1 ? Real(1) : Real(0);
    const TaylorVariable<Real> t(&evaluation, time, time[k], 1);
    output_count_ = rhs(pass.x, t, pass.dxdt, pass.outputs);
    for (std::size_t i = 0; i < N; ++i) {
      const Real f = pass.dxdt[i].coefficient(k);
      rate_row(i)[k] = f;
      if (k < order) state_row(i)[k + 1] = f * taylor_reciprocal<Real>(k + 1);
    }
    for (int j = 0; j < output_count_; ++j) {
      // an output that is a constant or the time gets a row of its own
      const TaylorVariable<Real>& out = pass.outputs[j];
      Real* out_row = out.is_constant() ? evaluation.take_row() : out.row();
      out_row[k] = out.coefficient(k);
      output_rows_[j] = out_row;
    }
  }

 public:
  // Whether lane `lane` of a pass over lanes has a sign that needs its
  // slope (signs_need_slope).
  template <class Tape, class LaneRows>
  static bool lane_needs_slope(const LaneRows& lanes, const Tape& tape, int lane) {
    for (int i = 0; i < tape.sign_count(); ++i) {
      const double a0 = lanes.coefficient(tape.sign_row(i), 0, lane);
      const double a1 = lanes.coefficient(tape.sign_row(i), 1, lane);
      if (detail::near_zero(a0, a1) && detail::sign_of(a1) != detail::sign_of(a0)) return true;
    }
    return false;
  }

  // This series' coefficients from lane `lane` of a pass over lanes
  // (integrate/series_tape.hpp: `lanes` computed from `tape`, this series'
  // own order-0 recording, with others that record the same operations):
  // every row, and whether its signs need their slope, as evaluate() would
  // have left them (evaluating again with the slope reads the previous
  // evaluation's rows: a batch's stepper takes its lane only then, and
  // otherwise reads it in place).
  template <class Tape, class LaneRows>
  void take_lane(const LaneRows& lanes, const Tape& tape, int lane, int order) {
    static_assert(std::is_same_v<Real, double>);
    needs_slope_ = lane_needs_slope(lanes, tape, lane);
    for (int r = 0; r < tape.rows_taken(); ++r)
      lanes.copy_lane(r, order, lane, row(static_cast<std::size_t>(r)));
    output_count_ = tape.output_count();
    for (int j = 0; j < output_count_; ++j)
      output_rows_[j] = row(static_cast<std::size_t>(tape.output_row(j)));
  }

 private:
  Real* row(std::size_t r) { return &rows_[r * Evaluation::stride]; }
  Real* state_row(std::size_t i) { return row(i); }
  Real* rate_row(std::size_t i) { return row(N + i); }

  typename Evaluation::Rows rows_{};
  std::array<const Real*, max_outputs> output_rows_{};
  int output_count_ = 0;
  bool needs_slope_ = false;
};

}  // namespace impactlab
