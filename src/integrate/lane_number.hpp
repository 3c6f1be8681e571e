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
#include <cstring>
#include <type_traits>

namespace impactlab {

// GCC's and Clang's vector extension for four doubles: a value the compiler
// keeps in registers (one AVX register, or two SSE2 registers on any
// x86-64), whose arithmetic is the IEEE operation lane by lane.
using LaneQuad = double __attribute__((vector_size(32)));

// Four lanes' bits as integers: a comparison's mask (all bits set where it
// holds), or a quad's bits for a bitwise operation.
using LaneQuadMask = long __attribute__((vector_size(32)));

// Whether the processor has AVX2, for which a pass over lanes
// (integrate/series_tape.cpp) is compiled a second time (four lanes in one
// register), chosen at run time so that the build runs on any x86-64:
// without it the pass runs in SSE2 registers, with the same results.
inline bool lane_passes_available() {
#if defined(__x86_64__) && defined(__GNUC__)
  return __builtin_cpu_supports("avx2");
#else
  return true;
#endif
}

// B lanes (a multiple of four) as B/4 quads: each operation is B/4
// independent vector operations, so that where one chain of recurrences
// waits on the latency of the one before, the others fill the ports. (A
// single vector of eight doubles would not do: without AVX-512 GCC splits
// it through memory.)
// Aligned to a quad's 32 bytes: GCC aligns a vector of four doubles to 16
// bytes where AVX is off, as in the default build, and to 32 inside a
// function compiled for AVX2, which then moves it with aligned loads and
// stores.
template <int B>
struct alignas(32) LaneNumber {
  static_assert(B > 0 && B % 4 == 0, "lanes come in quads");
  static constexpr int width = B;
  static constexpr int quads = B / 4;
  LaneQuad quad[quads];

  LaneNumber() = default;
  LaneNumber(double value) {  // NOLINT(google-explicit-constructor): a constant in every lane
    // copied in as bytes: assigned lane by lane, or as a vector's braces,
    // GCC built a zero from halves with the register form of vmovq
    // (66 0F D6), which valgrind cannot run
    const double lanes[4] = {value, value, value, value};
    for (int q = 0; q < quads; ++q) std::memcpy(&quad[q], lanes, sizeof lanes);
  }

  [[nodiscard]] double lane(int i) const { return quad[i / 4][i % 4]; }
  void set_lane(int i, double value) { quad[i / 4][i % 4] = value; }

  friend LaneNumber operator+(const LaneNumber& a, const LaneNumber& b) {
    LaneNumber r;
    for (int q = 0; q < quads; ++q) r.quad[q] = a.quad[q] + b.quad[q];
    return r;
  }
  friend LaneNumber operator-(const LaneNumber& a, const LaneNumber& b) {
    LaneNumber r;
    for (int q = 0; q < quads; ++q) r.quad[q] = a.quad[q] - b.quad[q];
    return r;
  }
  friend LaneNumber operator*(const LaneNumber& a, const LaneNumber& b) {
    LaneNumber r;
    for (int q = 0; q < quads; ++q) r.quad[q] = a.quad[q] * b.quad[q];
    return r;
  }
  friend LaneNumber operator/(const LaneNumber& a, const LaneNumber& b) {
    LaneNumber r;
    for (int q = 0; q < quads; ++q) r.quad[q] = a.quad[q] / b.quad[q];
    return r;
  }
  friend LaneNumber operator-(const LaneNumber& a) {
    LaneNumber r;
    for (int q = 0; q < quads; ++q) r.quad[q] = -a.quad[q];
    return r;
  }
  LaneNumber& operator+=(const LaneNumber& b) { return *this = *this + b; }
  LaneNumber& operator-=(const LaneNumber& b) { return *this = *this - b; }
  LaneNumber& operator*=(const LaneNumber& b) { return *this = *this * b; }
  LaneNumber& operator/=(const LaneNumber& b) { return *this = *this / b; }

  friend LaneNumber sqrt(const LaneNumber& a) {
    LaneNumber r;
    for (int i = 0; i < B; ++i) r.set_lane(i, std::sqrt(a.lane(i)));
    return r;
  }
  // the sign bit cleared, as std::fabs does (bit for bit, a NaN's too)
  friend LaneNumber fabs(const LaneNumber& a) {
    constexpr long all_but_sign = ~(1L << 63);
    const LaneQuadMask keep = {all_but_sign, all_but_sign, all_but_sign, all_but_sign};
    LaneNumber r;
    for (int q = 0; q < quads; ++q)
      r.quad[q] = reinterpret_cast<LaneQuad>(reinterpret_cast<LaneQuadMask>(a.quad[q]) & keep);
    return r;
  }
};

// Lane-by-lane comparisons of B lanes: all bits set in a lane where it
// holds, none where not (GCC's and Clang's vector comparisons); LaneQuadMask
// (above) holds four of them.

template <int B>
struct alignas(32) LaneMask {
  LaneQuadMask quad[B / 4];

  friend LaneMask operator&(const LaneMask& a, const LaneMask& b) {
    LaneMask r;
    for (int q = 0; q < B / 4; ++q) r.quad[q] = a.quad[q] & b.quad[q];
    return r;
  }
  friend LaneMask operator|(const LaneMask& a, const LaneMask& b) {
    LaneMask r;
    for (int q = 0; q < B / 4; ++q) r.quad[q] = a.quad[q] | b.quad[q];
    return r;
  }
  friend LaneMask operator!(const LaneMask& a) {
    LaneMask r;
    for (int q = 0; q < B / 4; ++q) r.quad[q] = ~a.quad[q];
    return r;
  }
  // where a and b agree
  friend LaneMask operator==(const LaneMask& a, const LaneMask& b) {
    LaneMask r;
    for (int q = 0; q < B / 4; ++q) r.quad[q] = a.quad[q] == b.quad[q];
    return r;
  }
  // whether the comparison holds in any lane
  friend bool any_lane(const LaneMask& a) {
    for (int i = 0; i < B; ++i)
      if (a.quad[i / 4][i % 4] != 0) return true;
    return false;
  }
};

#define IMPACTLAB_LANE_COMPARISON(op)                                             \
  template <int B>                                                              \
  LaneMask<B> operator op(const LaneNumber<B>& a, const LaneNumber<B>& b) {     \
    LaneMask<B> r;                                                              \
    for (int q = 0; q < B / 4; ++q) r.quad[q] = a.quad[q] op b.quad[q];         \
    return r;                                                                   \
  }
IMPACTLAB_LANE_COMPARISON(<)
IMPACTLAB_LANE_COMPARISON(>)
IMPACTLAB_LANE_COMPARISON(<=)
IMPACTLAB_LANE_COMPARISON(==)
#undef IMPACTLAB_LANE_COMPARISON

// a where the mask holds, b where not, lane by lane
template <int B>
LaneNumber<B> select(const LaneMask<B>& mask, const LaneNumber<B>& a, const LaneNumber<B>& b) {
  LaneNumber<B> r;
  for (int q = 0; q < B / 4; ++q) r.quad[q] = mask.quad[q] ? a.quad[q] : b.quad[q];
  return r;
}

template <class T>
inline constexpr bool is_lane_number = false;
template <int B>
inline constexpr bool is_lane_number<LaneNumber<B>> = true;

// The value of a constant (the same in every lane) as a double.
template <class Real>
double constant_value(const Real& value) {
  if constexpr (is_lane_number<Real>)
    return value.lane(0);
  else
    return static_cast<double>(value);
}

}  // namespace impactlab
