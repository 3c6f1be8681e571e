// Forward-mode automatic differentiation: a dual number v + d ε (ε² = 0)
// carries a value and its derivative along one direction through the same
// arithmetic and elementary functions a right-hand side written over a number
// type calls unqualified (core/fast_trig.hpp's sin_angle and cos_phase,
// core/sign.hpp's sign, fabs, sin, cos).
//
// Number is double, or the Taylor series' number type TaylorVariable
// (integrate/taylor_series.hpp): Dual<TaylorVariable> computes the series of
// a right-hand side's value and of its directional derivative together, so
// the series of the variational equations comes from the system's own
// right-hand side (analysis/variational.hpp).
//
// A derivative known to be zero (a function of the time alone, a constant)
// is kept as the constant zero and skipped in the product and chain rules:
// on a series, 0 · a would otherwise cost a product per operation (a Number
// that can tell, through is_constant() and constant(), is asked; double is
// never: its arithmetic is the plain formulas).
#pragma once

#include <cmath>
#include <concepts>

#include "core/fast_trig.hpp"
#include "core/sign.hpp"

namespace impactlab {

template <class Number>
class Dual {
 public:
  Dual() = default;
  Dual(const Number& value, const Number& derivative) : value_(value), derivative_(derivative) {}
  // a value whose derivative is zero: a constant, a function of the time
  // alone (NOLINT: constants mix in freely, as in a right-hand side's
  // dxdt[2] = 0.0)
  Dual(const Number& value) : value_(value), derivative_(0.0) {}  // NOLINT
  Dual(double constant)                                           // NOLINT
    requires(!std::same_as<Number, double>)
      : value_(constant), derivative_(0.0) {}

  [[nodiscard]] const Number& value() const { return value_; }
  [[nodiscard]] const Number& derivative() const { return derivative_; }

  Dual& operator+=(const Dual& b) { return *this = *this + b; }
  Dual& operator-=(const Dual& b) { return *this = *this - b; }
  Dual& operator*=(const Dual& b) { return *this = *this * b; }
  Dual& operator/=(const Dual& b) { return *this = *this / b; }

 private:
  Number value_{};
  Number derivative_{};
};

namespace detail {

// whether v is the constant zero, as far as its type can tell without a
// branch on a computed value (double: never)
template <class Number>
bool known_zero(const Number& v) {
  if constexpr (requires { v.is_constant(); v.constant(); })
    return v.is_constant() && v.constant() == 0.0;
  else
    return false;
}

// f' · d (the chain rule), the constant zero where d is
template <class Number>
Number chain(const Number& slope, const Number& d) {
  if (known_zero(d)) return Number(0.0);
  return slope * d;
}

// a + b, either of which may be the constant zero
template <class Number>
Number sum(const Number& a, const Number& b) {
  if (known_zero(a)) return b;
  if (known_zero(b)) return a;
  return a + b;
}

}  // namespace detail

// --- arithmetic ---

template <class Number>
Dual<Number> operator+(const Dual<Number>& a, const Dual<Number>& b) {
  return {a.value() + b.value(), detail::sum(a.derivative(), b.derivative())};
}
template <class Number>
Dual<Number> operator-(const Dual<Number>& a, const Dual<Number>& b) {
  const Number d = detail::known_zero(b.derivative()) ? a.derivative()
                   : detail::known_zero(a.derivative())
                       ? Number(-b.derivative())
                       : Number(a.derivative() - b.derivative());
  return {a.value() - b.value(), d};
}
template <class Number>
Dual<Number> operator-(const Dual<Number>& a) {
  return {-a.value(), detail::known_zero(a.derivative()) ? a.derivative() : -a.derivative()};
}
// (a b)' = a' b + a b'
template <class Number>
Dual<Number> operator*(const Dual<Number>& a, const Dual<Number>& b) {
  return {a.value() * b.value(), detail::sum(detail::chain(b.value(), a.derivative()),
                                             detail::chain(a.value(), b.derivative()))};
}
// (a / b)' = (a' − q b') / b, q = a / b
template <class Number>
Dual<Number> operator/(const Dual<Number>& a, const Dual<Number>& b) {
  const Number q = a.value() / b.value();
  if (detail::known_zero(b.derivative())) {
    if (detail::known_zero(a.derivative())) return {q, Number(0.0)};
    return {q, a.derivative() / b.value()};
  }
  if (detail::known_zero(a.derivative())) return {q, -(q * b.derivative()) / b.value()};
  return {q, (a.derivative() - q * b.derivative()) / b.value()};
}

// with a double on either side: a constant, its derivative zero
template <class Number>
Dual<Number> operator+(const Dual<Number>& a, double c) {
  return {a.value() + c, a.derivative()};
}
template <class Number>
Dual<Number> operator+(double c, const Dual<Number>& a) {
  return {c + a.value(), a.derivative()};
}
template <class Number>
Dual<Number> operator-(const Dual<Number>& a, double c) {
  return {a.value() - c, a.derivative()};
}
template <class Number>
Dual<Number> operator-(double c, const Dual<Number>& a) {
  return {c - a.value(), detail::known_zero(a.derivative()) ? a.derivative() : -a.derivative()};
}
template <class Number>
Dual<Number> operator*(const Dual<Number>& a, double c) {
  return {a.value() * c, detail::chain(Number(c), a.derivative())};
}
template <class Number>
Dual<Number> operator*(double c, const Dual<Number>& a) {
  return {c * a.value(), detail::chain(Number(c), a.derivative())};
}
template <class Number>
Dual<Number> operator/(const Dual<Number>& a, double c) {
  if (detail::known_zero(a.derivative())) return {a.value() / c, a.derivative()};
  return {a.value() / c, a.derivative() / c};
}
// (c / b)' = −q b' / b, q = c / b
template <class Number>
Dual<Number> operator/(double c, const Dual<Number>& b) {
  const Number q = c / b.value();
  if (detail::known_zero(b.derivative())) return {q, Number(0.0)};
  return {q, -(q * b.derivative()) / b.value()};
}

// --- elementary functions, found by argument-dependent lookup ---

template <class Number>
Dual<Number> sin(const Dual<Number>& a) {
  using std::cos;
  using std::sin;
  return {sin(a.value()), detail::chain(Number(cos(a.value())), a.derivative())};
}
template <class Number>
Dual<Number> cos(const Dual<Number>& a) {
  using std::cos;
  using std::sin;
  return {cos(a.value()), detail::chain(Number(-sin(a.value())), a.derivative())};
}
// core/fast_trig.hpp's names: the value by the Number's own function, the
// derivative's factor by sin and cos
template <class Number>
Dual<Number> sin_angle(const Dual<Number>& a) {
  using std::cos;
  return {sin_angle(a.value()), detail::chain(Number(cos(a.value())), a.derivative())};
}
template <class Number>
Dual<Number> cos_phase(const Dual<Number>& a) {
  using std::sin;
  return {cos_phase(a.value()), detail::chain(Number(-sin(a.value())), a.derivative())};
}
// the sign is piecewise constant: derivative zero (the systems end a step at
// each of its jumps)
template <class Number>
Dual<Number> sign(const Dual<Number>& a) {
  return {sign(a.value()), Number(0.0)};
}
// |a| = sign(a) · a
template <class Number>
Dual<Number> fabs(const Dual<Number>& a) {
  return sign(a) * a;
}

}  // namespace impactlab
