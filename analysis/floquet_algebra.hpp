// The linear algebra of Floquet analysis on an N-dimensional tangent space:
// the multipliers (eigenvalues of the monodromy matrix) and the Newton step
// of shooting. N = 2 is solved in closed form here; larger N go to Eigen's
// dynamic-size decompositions, compiled once (floquet_eigenvalues.cpp,
// floquet_newton_step.cpp; their results are bit for bit those of the
// fixed-size ones), so that no analysis compiles Eigen's eigenvalue solver
// again per system and dimension.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <optional>
#include <utility>

#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

namespace detail {

// The n eigenvalues of the row-major n × n `matrix` into `values`, largest
// modulus first (of a complex pair, the positive imaginary part first); NaN
// where the matrix is not finite or its real Schur form does not converge.
void dense_eigenvalues(const double* matrix, std::size_t n, std::complex<double>* values);

// `step` solving (M − I) step = −residual for the row-major n × n `monodromy`
// by a fully pivoted LU decomposition; false where M − I is singular or not
// finite.
bool dense_newton_step(const double* monodromy, const double* residual, std::size_t n,
                       double* step);

}  // namespace detail

// Eigenvalues of an N × N matrix, largest modulus first (of a complex pair,
// the one with the positive imaginary part first): for N = 2 from the trace
// and determinant, otherwise from Eigen's real Schur form.
template <std::size_t N>
std::array<std::complex<double>, N> eigenvalues(const TangentMatrixOf<N>& m) {
  if constexpr (N == 2) {
    const double half_trace = 0.5 * (m[0][0] + m[1][1]);
    const double determinant = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    const std::complex<double> root =
        std::sqrt(std::complex<double>(half_trace * half_trace - determinant));
    std::complex<double> a = half_trace + root, b = half_trace - root;
    if (std::abs(b) > std::abs(a)) std::swap(a, b);
    return {a, b};
  } else {
    std::array<double, N * N> matrix;
    for (std::size_t i = 0; i < N; ++i) std::copy_n(m[i].begin(), N, matrix.begin() + i * N);
    std::array<std::complex<double>, N> values;
    detail::dense_eigenvalues(matrix.data(), N, values.data());
    return values;
  }
}

// δ solving (M − I) δ = −r; none where M − I is singular: Cramer's rule for
// N = 2, a fully pivoted LU decomposition otherwise. For N > 2, where M − I
// is singular because the orbit is one of a family (a direction along which
// the map is neutral, multiplier 1: the free spin of a ball whose impacts
// all slide), the least-squares step of least norm: Newton then converges
// to the member of the family nearest the guess.
template <std::size_t N>
std::optional<TangentVectorOf<N>> newton_step(const TangentMatrixOf<N>& monodromy,
                                              const TangentVectorOf<N>& residual) {
  if constexpr (N == 2) {
    const double r0 = residual[0], r1 = residual[1];
    const double a = monodromy[0][0] - 1.0, b = monodromy[0][1];
    const double c = monodromy[1][0], d = monodromy[1][1] - 1.0;
    const double determinant = a * d - b * c;
    if (determinant == 0.0 || !std::isfinite(determinant)) return std::nullopt;
    return TangentVectorOf<N>{(-r0 * d + r1 * b) / determinant, (-a * r1 + c * r0) / determinant};
  } else {
    std::array<double, N * N> matrix;
    for (std::size_t i = 0; i < N; ++i)
      std::copy_n(monodromy[i].begin(), N, matrix.begin() + i * N);
    TangentVectorOf<N> step;
    if (!detail::dense_newton_step(matrix.data(), residual.data(), N, step.data()))
      return std::nullopt;
    return step;
  }
}

}  // namespace impactlab
