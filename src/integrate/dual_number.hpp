// Forward-mode automatic differentiation: a dual number v + Σ_i d_i ε_i
// (ε_i ε_j = 0) carries a value and its derivatives along `Directions`
// directions through the same arithmetic and elementary functions a
// right-hand side written over a number type calls unqualified
// (core/fast_trig.hpp's sin_angle, cos_phase and sin_phase, core/sign.hpp's
// sign, fabs, sin, cos). The value is computed once for all the directions,
// and each direction's derivative by the same operations as a one-direction
// number seeded with that direction alone would use (the same results, bit
// for bit).
//
// Number is double, or the Taylor series' number type TaylorVariable
// (integrate/taylor_series.hpp): Dual<TaylorVariable, N> computes the series
// of a right-hand side's value and of its derivatives along N directions
// together, so the series of the variational equations comes from one run of
// the system's own right-hand side (analysis/variational.hpp: one direction
// per column of the fundamental matrix).
//
// A derivative known to be zero (a function of the time alone, a constant)
// is kept as the constant zero and skipped, direction by direction, in the
// product and chain rules: on a series, 0 · a would otherwise cost a product
// per operation (a Number that can tell, through is_constant() and
// constant(), is asked; double is never: its arithmetic is the plain
// formulas). Whether a series is a constant does not depend on its
// coefficients' values, so these branches take the same way at every order,
// as the series' evaluation requires.
#pragma once

#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <utility>

#include <impactlab/core/fast_trig.hpp>
#include <impactlab/core/sign.hpp>

namespace impactlab {

template <class Number, std::size_t Directions = 1>
class Dual {
 public:
  static_assert(Directions >= 1);
  using Derivatives = std::array<Number, Directions>;

  Dual() = default;
  Dual(const Number& value, const Derivatives& derivatives)
      : value_(value), derivatives_(derivatives) {}
  // one direction: v + d ε
  Dual(const Number& value, const Number& derivative)
    requires(Directions == 1)
      : value_(value), derivatives_{derivative} {}
  // a value whose derivatives are zero: a constant, a function of the time
  // alone (NOLINT: constants mix in freely, as in a right-hand side's
  // dxdt[2] = 0.0)
  Dual(const Number& value) : value_(value), derivatives_(zero_derivatives()) {}  // NOLINT
  Dual(double constant)                                                          // NOLINT
    requires(!std::same_as<Number, double>)
      : value_(constant), derivatives_(zero_derivatives()) {}

  [[nodiscard]] const Number& value() const { return value_; }
  // the derivative along direction `direction` (0 <= direction < Directions)
  [[nodiscard]] const Number& derivative(std::size_t direction) const {
    return derivatives_[direction];
  }
  [[nodiscard]] const Number& derivative() const
    requires(Directions == 1)
  {
    return derivatives_[0];
  }
  [[nodiscard]] const Derivatives& derivatives() const { return derivatives_; }

  Dual& operator+=(const Dual& b) { return *this = *this + b; }
  Dual& operator-=(const Dual& b) { return *this = *this - b; }
  Dual& operator*=(const Dual& b) { return *this = *this * b; }
  Dual& operator/=(const Dual& b) { return *this = *this / b; }

 private:
  static Derivatives zero_derivatives() {
    Derivatives zeros;
    zeros.fill(Number(0.0));
    return zeros;
  }

  Number value_{};
  Derivatives derivatives_{};
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

// whether every derivative is the constant zero
template <class Number, std::size_t Directions>
bool all_known_zero(const std::array<Number, Directions>& derivatives) {
  for (const Number& d : derivatives)
    if (!known_zero(d)) return false;
  return true;
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

// −d, the constant zero where d is
template <class Number>
Number negated(const Number& d) {
  if (known_zero(d)) return d;
  return -d;
}

// the derivatives along every direction, direction(i) for direction i, in
// the order of the directions (the series' rows are taken in that order).
// Each is constructed in place by a pack expansion: with a loop assigning
// into a default-constructed array instead, the Taylor runs of
// benchmarks/lyapunov_taylor (500 periods, rtol 1e-12) took 19.6 ms against
// 18.5 ms for one run per direction, and 7.6 ms with this.
template <class Number, std::size_t Directions, class PerDirection>
std::array<Number, Directions> each_direction(const PerDirection& direction) {
  return [&]<std::size_t... i>(std::index_sequence<i...>) {
    return std::array<Number, Directions>{direction(i)...};
  }(std::make_index_sequence<Directions>{});
}

}  // namespace detail

// --- arithmetic ---

template <class Number, std::size_t Directions>
Dual<Number, Directions> operator+(const Dual<Number, Directions>& a,
                                   const Dual<Number, Directions>& b) {
  return {a.value() + b.value(), detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::sum(a.derivative(i), b.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator-(const Dual<Number, Directions>& a,
                                   const Dual<Number, Directions>& b) {
  return {a.value() - b.value(),
          detail::each_direction<Number, Directions>([&](std::size_t i) -> Number {
            const Number& da = a.derivative(i);
            const Number& db = b.derivative(i);
            if (detail::known_zero(db)) return da;
            if (detail::known_zero(da)) return -db;
            return da - db;
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator-(const Dual<Number, Directions>& a) {
  return {-a.value(), detail::each_direction<Number, Directions>(
                          [&](std::size_t i) { return detail::negated(a.derivative(i)); })};
}
// (a b)' = a' b + a b'
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator*(const Dual<Number, Directions>& a,
                                   const Dual<Number, Directions>& b) {
  return {a.value() * b.value(), detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::sum(detail::chain(b.value(), a.derivative(i)),
                               detail::chain(a.value(), b.derivative(i)));
          })};
}
// (a / b)' = (a' − q b') / b, q = a / b
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator/(const Dual<Number, Directions>& a,
                                   const Dual<Number, Directions>& b) {
  const Number q = a.value() / b.value();
  return {q, detail::each_direction<Number, Directions>([&](std::size_t i) -> Number {
            const Number& da = a.derivative(i);
            const Number& db = b.derivative(i);
            if (detail::known_zero(db)) {
              if (detail::known_zero(da)) return Number(0.0);
              return da / b.value();
            }
            if (detail::known_zero(da)) return -(q * db) / b.value();
            return (da - q * db) / b.value();
          })};
}

// with a double on either side: a constant, its derivatives zero
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator+(const Dual<Number, Directions>& a, double c) {
  return {a.value() + c, a.derivatives()};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator+(double c, const Dual<Number, Directions>& a) {
  return {c + a.value(), a.derivatives()};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator-(const Dual<Number, Directions>& a, double c) {
  return {a.value() - c, a.derivatives()};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator-(double c, const Dual<Number, Directions>& a) {
  return {c - a.value(), detail::each_direction<Number, Directions>(
                             [&](std::size_t i) { return detail::negated(a.derivative(i)); })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator*(const Dual<Number, Directions>& a, double c) {
  return {a.value() * c, detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(Number(c), a.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator*(double c, const Dual<Number, Directions>& a) {
  return {c * a.value(), detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(Number(c), a.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator/(const Dual<Number, Directions>& a, double c) {
  return {a.value() / c, detail::each_direction<Number, Directions>([&](std::size_t i) -> Number {
            const Number& d = a.derivative(i);
            if (detail::known_zero(d)) return d;
            return d / c;
          })};
}
// (c / b)' = −q b' / b, q = c / b
template <class Number, std::size_t Directions>
Dual<Number, Directions> operator/(double c, const Dual<Number, Directions>& b) {
  const Number q = c / b.value();
  return {q, detail::each_direction<Number, Directions>([&](std::size_t i) -> Number {
            const Number& db = b.derivative(i);
            if (detail::known_zero(db)) return Number(0.0);
            return -(q * db) / b.value();
          })};
}

// --- elementary functions, found by argument-dependent lookup ---

// sin and cos of the value come from one call of sin_and_cos_of (double:
// core/fast_trig.hpp's; a series: integrate/taylor_series.hpp's, one run of
// the coupled recurrence for both), the one the derivatives' factor needs
// too: sin a = s + c Σ d_i ε_i, cos a = c − s Σ d_i ε_i
template <class Number, std::size_t Directions>
Dual<Number, Directions> sin(const Dual<Number, Directions>& a) {
  const SineAndCosine<Number> value = sin_and_cos_of(a.value());
  return {value.sine, detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(value.cosine, a.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> cos(const Dual<Number, Directions>& a) {
  const SineAndCosine<Number> value = sin_and_cos_of(a.value());
  // −s only where a derivative needs it (cos ωt has none)
  if (detail::all_known_zero(a.derivatives())) return Dual<Number, Directions>(value.cosine);
  const Number slope = -value.sine;
  return {value.cosine, detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(slope, a.derivative(i));
          })};
}
// core/fast_trig.hpp's names: sin and cos above, whose double values are
// fast_trig's (sin_cos_phase: the cosine is cos_phase's and the sine
// sin_phase's bit for bit, the sine sin_angle's for |θ| <= π/4 and within a
// few ulps of it beyond); on a series all five are the same functions
template <class Number, std::size_t Directions>
Dual<Number, Directions> sin_angle(const Dual<Number, Directions>& a) {
  return sin(a);
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> cos_phase(const Dual<Number, Directions>& a) {
  return cos(a);
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> sin_phase(const Dual<Number, Directions>& a) {
  return sin(a);
}
// exp a = e + e Σ d_i ε_i, log a = log v + Σ (d_i / v) ε_i, √a = r + Σ
// (d_i / 2r) ε_i, a^α = p + Σ (α p / v) d_i ε_i (v a's value, α a constant)
template <class Number, std::size_t Directions>
Dual<Number, Directions> exp(const Dual<Number, Directions>& a) {
  using std::exp;
  const Number value = exp(a.value());
  return {value, detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(value, a.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> log(const Dual<Number, Directions>& a) {
  using std::log;
  if (detail::all_known_zero(a.derivatives())) return Dual<Number, Directions>(log(a.value()));
  const Number slope = Number(1.0) / a.value();
  return {log(a.value()), detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(slope, a.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> sqrt(const Dual<Number, Directions>& a) {
  using std::sqrt;
  const Number value = sqrt(a.value());
  if (detail::all_known_zero(a.derivatives())) return Dual<Number, Directions>(value);
  const Number slope = Number(0.5) / value;
  return {value, detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(slope, a.derivative(i));
          })};
}
template <class Number, std::size_t Directions>
Dual<Number, Directions> pow(const Dual<Number, Directions>& a, double alpha) {
  using std::pow;
  const Number value = pow(a.value(), alpha);
  if (detail::all_known_zero(a.derivatives())) return Dual<Number, Directions>(value);
  const Number slope = (alpha * value) / a.value();
  return {value, detail::each_direction<Number, Directions>([&](std::size_t i) {
            return detail::chain(slope, a.derivative(i));
          })};
}

// the sign is piecewise constant: derivatives zero (the systems end a step
// at each of its jumps)
template <class Number, std::size_t Directions>
Dual<Number, Directions> sign(const Dual<Number, Directions>& a) {
  return Dual<Number, Directions>(sign(a.value()));
}
// |a| = sign(a) · a
template <class Number, std::size_t Directions>
Dual<Number, Directions> fabs(const Dual<Number, Directions>& a) {
  return sign(a) * a;
}

}  // namespace impactlab
