// sin and cos for right-hand sides and witnesses evaluated millions of
// times: the cosine and sine of a forcing phase ωt that grows without bound
// over a run, and the sine of an angle bounded by the walls.
//
// glibc's cos takes its argument-reduction path for |x| > 2.43 (about 98
// instructions per call with its rounding-mode guard in a callgrind profile
// of the pendulum, where cos ωt was a quarter of all instructions), and its
// short path for small arguments still costs about 40. Here the phase is
// reduced inline by Cody–Waite's method, x = n π/2 + r with π/2 split into
// three parts of 33 bits and a tail (fdlibm's pio2_1, pio2_2, pio2_3,
// pio2_3t; n · part is exact for |n| < 2^20, |x| < 1.6e6 rad; beyond that
// std::cos is called), and
// sin r, cos r (|r| <= π/4) are fdlibm's kernel polynomials. Tests check both
// against long double sinl/cosl to a few ulps (std::sin and std::cos are
// within 1 ulp), so a run agrees with one using the library's functions to
// round-off, not bit for bit.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace impactlab {

// sin r and cos r for |r| <= π/4: fdlibm's kernels (__kernel_sin,
// __kernel_cos: minimax polynomials in z = r², error below 2^-58 before
// rounding), their polynomials evaluated by Estrin's scheme, whose shorter
// chain of dependent operations matters more here than the operation count
inline double sin_quarter(double r) {
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  const double z = r * r, z2 = z * z;
  const double p = (S1 + S2 * z) + z2 * ((S3 + S4 * z) + z2 * (S5 + S6 * z));
  return r + r * z * p;
}

inline double cos_quarter(double r) {
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double z = r * r, z2 = z * z;
  const double p = z * ((C1 + C2 * z) + z2 * ((C3 + C4 * z) + z2 * (C5 + C6 * z)));
  // 1 − z/2 + z p with the rounding of 1 − z/2 recovered (fdlibm's form)
  const double half_z = 0.5 * z;
  const double w = 1.0 - half_z;
  return w + (((1.0 - w) - half_z) + z * p);
}

// x = n π/2 + r, |r| <= π/4, for |x| below `phase_reduction_limit`: r, and
// n mod 4 (the quadrant)
inline constexpr double phase_reduction_limit = 1.6e6;  // |n| < 2^20 below this (rad)
inline int reduce_phase(double x, double& r) {
  constexpr double two_over_pi = 6.36619772367581382433e-01;
  constexpr double pio2_1 = 1.57079632673412561417e+00;  // first 33 bits of π/2
  constexpr double pio2_2 = 6.07710050630396597660e-11;  // next 33 bits
  constexpr double pio2_3 = 2.02226624871116645580e-21;  // next 33 bits
  constexpr double pio2_3t = 8.47842766036889956997e-32; // the rest of π/2, rounded
  constexpr double round_shift = 0x1.8p52;               // adding it rounds to an integer
  const double n = (x * two_over_pi + round_shift) - round_shift;
  r = (((x - n * pio2_1) - n * pio2_2) - n * pio2_3) - n * pio2_3t;
  return static_cast<int>(static_cast<std::int64_t>(n) & 3);
}

// cos x for a phase x = ωt (rad) of any size
inline double cos_phase(double x) {
  if (!(std::fabs(x) < phase_reduction_limit)) return std::cos(x);
  double r = 0.0;
  switch (reduce_phase(x, r)) {
    case 0: return cos_quarter(r);
    case 1: return -sin_quarter(r);
    case 2: return -cos_quarter(r);
    default: return sin_quarter(r);
  }
}

// sin x for a phase x = ωt (rad) of any size: sin_cos_phase's sine, bit for bit
inline double sin_phase(double x) {
  if (!(std::fabs(x) < phase_reduction_limit)) return std::sin(x);
  double r = 0.0;
  switch (reduce_phase(x, r)) {
    case 0: return sin_quarter(r);
    case 1: return cos_quarter(r);
    case 2: return -sin_quarter(r);
    default: return -cos_quarter(r);
  }
}

// sin x and cos x together, for any x (rad): one reduction for both (the
// order-0 coefficients of a Taylor series' sin/cos pair); the cosine is
// cos_phase's and the sine sin_phase's, bit for bit
inline void sin_cos_phase(double x, double& s, double& c) {
  if (!(std::fabs(x) < phase_reduction_limit)) {
    s = std::sin(x);
    c = std::cos(x);
    return;
  }
  double r = 0.0;
  const int quadrant = reduce_phase(x, r);
  const double sin_r = sin_quarter(r), cos_r = cos_quarter(r);
  switch (quadrant) {
    case 0: s = sin_r; c = cos_r; return;
    case 1: s = cos_r; c = -sin_r; return;
    case 2: s = -sin_r; c = -cos_r; return;
    default: s = -cos_r; c = sin_r; return;
  }
}

// sin x and cos x of one argument, computed together
template <class Number>
struct SineAndCosine {
  Number sine;
  Number cosine;
};

// sin_cos_phase's pair, for a generic caller that calls sin_and_cos_of
// unqualified (integrate/dual_number.hpp; a series type supplies its own,
// integrate/taylor_series.hpp)
inline SineAndCosine<double> sin_and_cos_of(double x) {
  SineAndCosine<double> result{};
  sin_cos_phase(x, result.sine, result.cosine);
  return result;
}

// sin θ (rad), by the series where |θ| <= π/4
inline double sin_angle(double theta) {
  return std::fabs(theta) <= 0.25 * std::numbers::pi ? sin_quarter(theta) : std::sin(theta);
}

}  // namespace impactlab
