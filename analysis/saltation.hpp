// The saltation matrix: how a perturbation of the state just before an event
// maps to one just after it. It is not the reset's Jacobian alone: a
// perturbed trajectory reaches the event surface earlier or later, and during
// that time difference it moves with the vector field of the other mode.
//
// For an event h(x, t) = 0 with reset x⁺ = g(x⁻, t):
//     S = G + (f⁺ − G f⁻ − ∂g/∂t) ∇hᵀ / ḣ,    ḣ = ∇h · f⁻ + ∂h/∂t
// with G = ∂g/∂x, f⁻ and f⁺ the vector fields of the modes before and after
// (f⁺ at the time the system continues from: later than the event where an
// accumulation of impacts was jumped over),
// all on the system's tangent space (core/has_jacobian.hpp: (q, q̇), or a
// model file's N states). ḣ is the witness's rate along the flow
// (WitnessSample::rate), so the explicit time dependence of a moving wall is
// in it. References: Aizerman & Gantmacher (1958); Müller (1995), Chaos,
// Solitons & Fractals 5(9); Leine & Nijmeijer, Dynamics and Bifurcations of
// Non-Smooth Mechanical Systems (2004), ch. 3.
//
// Special cases: a grazing touch (ḣ = 0, where S is singular) is passed with
// the identity; a transition that collapses nearby states into one (rest on a
// wall after an accumulation, a release at a time set by the forcing) has S = 0;
// an event on a switch of its reset has only one side's (Saltation::one_sided).
#pragma once

#include <cmath>
#include <cstddef>

#include <impactlab/core/has_jacobian.hpp>

namespace impactlab {

template <std::size_t N>
struct Saltation {
  TangentMatrixOf<N> matrix{};
  bool one_sided = false;  // the reset's derivative is one side's (ResetJacobianOf::one_sided)
};

template <HasJacobian System>
Saltation<tangent_dimension_of<System>> saltation_matrix(const System& system, typename System::Mode mode_before,
                               std::size_t witness, CrossingKind crossing,
                               const typename System::State& x_before, double t,
                               const Transition<typename System::State, typename System::Mode>&
                                   after) {
  constexpr std::size_t n = tangent_dimension_of<System>;
  using Matrix = TangentMatrixOf<n>;
  if (crossing == CrossingKind::grazing || after.stop) return {identity_reset<n>().state};
  const ResetJacobianOf<n> reset =
      system.reset_jacobian(mode_before, witness, crossing, x_before, t, after);
  if (reset.collapses) return {Matrix{}, reset.one_sided};

  const WitnessSample h = system.witness(mode_before, witness, x_before, t);
  if (h.rate == 0.0) return {reset.state, reset.one_sided};
  typename System::State f_before{}, f_after{};
  system.rhs(mode_before, x_before, f_before, t);
  system.rhs(after.mode, after.state, f_after, after.time);
  const TangentVectorOf<n> gradient =
      system.witness_gradient(mode_before, witness, x_before, t);

  Matrix s = reset.state;
  for (std::size_t i = 0; i < n; ++i) {
    // (f⁺ − G f⁻ − ∂g/∂t)_i
    double jump = f_after[i] - reset.time[i];
    for (std::size_t j = 0; j < n; ++j) jump -= reset.state[i][j] * f_before[j];
    for (std::size_t j = 0; j < n; ++j) s[i][j] += jump * gradient[j] / h.rate;
  }
  return {s, reset.one_sided};
}

template <std::size_t N>
TangentMatrixOf<N> multiply(const TangentMatrixOf<N>& a, const TangentMatrixOf<N>& b) {
  TangentMatrixOf<N> c{};
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < N; ++j)
      for (std::size_t k = 0; k < N; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

}  // namespace impactlab
