// The Floquet multipliers of a periodic orbit whose dimension is known at run
// time: the eigenvalues of its monodromy matrix M = ∂Pⁿ/∂x on the system's
// N-dimensional tangent space ((q, q̇), or a model file's N states), as
// continuation (branch_continuation.hpp, curve_continuation.hpp) stores it.
// They come from floquet_algebra.hpp's closed form (N = 2) and its solver
// compiled once (N > 2), which Newton shooting (floquet.hpp) uses too.
#pragma once

#include <complex>
#include <cstddef>
#include <limits>
#include <vector>

namespace impactlab {

// ∂Pⁿ/∂x, N × N, row-major: m[row][column].
using MonodromyMatrix = std::vector<std::vector<double>>;

// The Floquet multipliers (eigenvalues of M), largest modulus first (of a
// complex pair, the one with the positive imaginary part first); NaN where M
// is not finite or its real Schur form does not converge.
std::vector<std::complex<double>> multipliers_of(const MonodromyMatrix& m);

// The N multipliers of an orbit that has none (its map crosses an event with
// a one-sided tangent map): NaN.
inline std::vector<std::complex<double>> missing_multipliers(std::size_t n) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return std::vector<std::complex<double>>(n, {nan, nan});
}

// The eigenvector of M for the real multiplier nearest `multiplier`, unit
// length: the direction a period-doubled orbit leaves along (multiplier −1).
std::vector<double> eigenvector_for(const MonodromyMatrix& m, double multiplier);

}  // namespace impactlab
