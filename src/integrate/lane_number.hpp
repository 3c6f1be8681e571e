// LaneNumber<B>: B doubles that every arithmetic operation acts on lane by
// lane, so that the Taylor recurrences (integrate/taylor_series.hpp) run over
// B series at once, in SIMD registers where the target has them (plain loops
// over a fixed-size array, which the compiler vectorises: SSE2 on any x86-64,
// AVX where the build enables it). Each lane's result is the IEEE result of
// the same operation on that lane's doubles, in the same order: a lane's
// coefficients are those the series of double would give, to the last bit
// (no FMA contraction: the build is ISO C++20, -ffp-contract=off).
#pragma once

#include <cmath>
#include <type_traits>

namespace impactlab {

// GCC's and Clang's vector extension for B doubles: a value the compiler
// keeps in registers (two SSE2 registers for four doubles on any x86-64),
// whose arithmetic is the IEEE operation lane by lane. (The attribute cannot
// take a size that depends on a template parameter: one type per width.)
template <int B>
struct LaneVector;
template <>
struct LaneVector<2> {
  typedef double type __attribute__((vector_size(16)));
};
template <>
struct LaneVector<4> {
  typedef double type __attribute__((vector_size(32)));
};
template <>
struct LaneVector<8> {
  typedef double type __attribute__((vector_size(64)));
};

// Whether the processor has AVX2, for which a pass over lanes
// (integrate/series_tape.cpp) is compiled a second time (four lanes in one
// register), chosen at run time so that the build runs on any x86-64:
// without it the pass runs in two SSE2 registers, with the same results.
inline bool lane_passes_available() {
#if defined(__x86_64__) && defined(__GNUC__)
  return __builtin_cpu_supports("avx2");
#else
  return true;
#endif
}

template <int B>
struct LaneNumber {
  static constexpr int width = B;
  using Vector = typename LaneVector<B>::type;
  Vector lane;

  LaneNumber() = default;
  LaneNumber(double value) {  // NOLINT(google-explicit-constructor): a constant in every lane
    for (int i = 0; i < B; ++i) lane[i] = value;
  }

  friend LaneNumber operator+(const LaneNumber& a, const LaneNumber& b) { return from(a.lane + b.lane); }
  friend LaneNumber operator-(const LaneNumber& a, const LaneNumber& b) { return from(a.lane - b.lane); }
  friend LaneNumber operator*(const LaneNumber& a, const LaneNumber& b) { return from(a.lane * b.lane); }
  friend LaneNumber operator/(const LaneNumber& a, const LaneNumber& b) { return from(a.lane / b.lane); }
  friend LaneNumber operator-(const LaneNumber& a) { return from(-a.lane); }
  LaneNumber& operator+=(const LaneNumber& b) { return *this = *this + b; }
  LaneNumber& operator-=(const LaneNumber& b) { return *this = *this - b; }
  LaneNumber& operator*=(const LaneNumber& b) { return *this = *this * b; }
  LaneNumber& operator/=(const LaneNumber& b) { return *this = *this / b; }

  friend LaneNumber fabs(const LaneNumber& a) {
    LaneNumber r;
    for (int i = 0; i < B; ++i) r.lane[i] = std::fabs(a.lane[i]);
    return r;
  }

 private:
  static LaneNumber from(const Vector& v) {
    LaneNumber r;
    r.lane = v;
    return r;
  }
};

template <class T>
inline constexpr bool is_lane_number = false;
template <int B>
inline constexpr bool is_lane_number<LaneNumber<B>> = true;

// The value of a constant (the same in every lane) as a double.
template <class Real>
double constant_value(const Real& value) {
  if constexpr (is_lane_number<Real>)
    return value.lane[0];
  else
    return static_cast<double>(value);
}

}  // namespace impactlab
