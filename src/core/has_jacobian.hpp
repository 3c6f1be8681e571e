// Systems that can linearise their own flow and events, for the variational
// equations, saltation matrices, Floquet multipliers and Lyapunov exponents
// (analysis/variational.hpp, analysis/saltation.hpp).
//
// The tangent space is that of the mechanical state: the first N state
// components, N = S::tangent_dimension where the system declares it (a model
// file's N states), 2 otherwise (q, q̇). Further components (the pendulum's
// friction work) are bookkeeping that never feeds back into the motion, so
// they are left out: a neutral bookkeeping direction would otherwise pin the
// largest Lyapunov exponent at zero.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <tuple>

#include <impactlab/core/hybrid_system.hpp>

namespace impactlab {

// the tangent space of a system that does not declare its own: (q, q̇)
inline constexpr std::size_t default_tangent_dimension = 2;

// An N × N matrix on the tangent space, row-major: m[row][column].
template <std::size_t N>
using TangentMatrixOf = std::array<std::array<double, N>, N>;
template <std::size_t N>
using TangentVectorOf = std::array<double, N>;
// the 2-state spelling (q, q̇)
using TangentMatrix = TangentMatrixOf<default_tangent_dimension>;
using TangentVector = TangentVectorOf<default_tangent_dimension>;

namespace detail {
template <class S>
constexpr std::size_t declared_tangent_dimension() {
  if constexpr (requires { S::tangent_dimension; })
    return S::tangent_dimension;
  else
    return default_tangent_dimension;
}
}  // namespace detail

// N of a system: S::tangent_dimension, or 2.
template <class S>
inline constexpr std::size_t tangent_dimension_of = detail::declared_tangent_dimension<S>();

// The linearisation of one event's transition x⁺ = g(x⁻, t).
template <std::size_t N>
struct ResetJacobianOf {
  TangentMatrixOf<N> state{};  // ∂g/∂x on the tangent space
  TangentVectorOf<N> time{};   // ∂g/∂t (the reset's explicit time dependence: a moving table)
  // The state after the event does not depend on the state before it: an
  // accumulation of impacts ending at rest on a wall, a release at a time set
  // by the forcing alone. Nearby states merge, so the saltation matrix is zero.
  bool collapses = false;
  // The matrix is one side's: the state before the event sits on a switch of
  // the reset (an impulse on the friction cone's edge, where sticking and
  // sliding give the same state after but not the same derivative), so no
  // derivative exists there (Transition::one_sided).
  bool one_sided = false;
};
using ResetJacobian = ResetJacobianOf<default_tangent_dimension>;

// The resets every impact oscillator here is made of:
// a grazing touch (or a run stopped at the event) leaves the state alone;
template <std::size_t N = default_tangent_dimension>
ResetJacobianOf<N> identity_reset() {
  ResetJacobianOf<N> reset;
  for (std::size_t i = 0; i < N; ++i) reset.state[i][i] = 1.0;
  return reset;
}
// an accumulation or a release at a time set by the forcing merges nearby states;
template <std::size_t N = default_tangent_dimension>
ResetJacobianOf<N> collapsed_reset() {
  ResetJacobianOf<N> reset;
  reset.collapses = true;
  return reset;
}
// an impact that puts q on the constraint and sets q̇⁺ = −r q̇⁻ (+ terms in t
// alone): ∂g/∂x = [[0, 0], [0, −r]] (one degree of freedom).
inline ResetJacobian restitution_reset(double restitution) {
  ResetJacobian reset;
  reset.state = {{{0.0, 0.0}, {0.0, -restitution}}};
  return reset;
}

template <class S>
concept HasJacobian =
    HybridSystem<S> && tangent_dimension_of<S> >= 1 &&
    tangent_dimension_of<S> <= std::tuple_size_v<typename S::State> &&
    requires(const S& system, typename S::Mode mode, std::size_t k, const typename S::State& x,
             double t, TangentMatrixOf<tangent_dimension_of<S>>& jacobian, CrossingKind crossing,
             const Transition<typename S::State, typename S::Mode>& after) {
      // ∂f/∂x of the mode's vector field on the tangent space
      { system.jacobian(mode, x, t, jacobian) };
      // ∂h/∂x of witness k on the tangent space; its ∂h/∂t is WitnessSample::rate − ∂h/∂x · f
      {
        system.witness_gradient(mode, k, x, t)
      } -> std::same_as<TangentVectorOf<tangent_dimension_of<S>>>;
      // the linearisation of the transition that on_event returned as `after`
      {
        system.reset_jacobian(mode, k, crossing, x, t, after)
      } -> std::same_as<ResetJacobianOf<tangent_dimension_of<S>>>;
      // whether the mode pins the state to a constraint (resting on a wall or
      // table): nearby states in it are the same state, tangent vectors are zero
      { system.pinned(mode) } -> std::convertible_to<bool>;
    };
// A system whose contact modes pin some tangent components and leave others
// free (a ball resting on a wall that may still spin) says which, where it
// has the member pinned_components(mode): an N-vector, 1 for each pinned
// component; the variational equations start with zero rows for those.


}  // namespace impactlab
