// Systems that can linearise their own flow and events, for the variational
// equations, saltation matrices, Floquet multipliers and Lyapunov exponents
// (analysis/variational.hpp, analysis/saltation.hpp).
//
// The tangent space is that of the mechanical state: the first two state
// components (q, q̇). Further components (the pendulum's friction work) are
// bookkeeping that never feeds back into the motion, so they are left out: a
// neutral bookkeeping direction would otherwise pin the largest Lyapunov
// exponent at zero.
#pragma once

#include <array>
#include <cstddef>

#include "core/hybrid_system.hpp"

namespace impactlab {

// dimension of the tangent space (q, q̇)
inline constexpr std::size_t tangent_dimension = 2;

// A 2 × 2 matrix on the tangent space, row-major: m[row][column].
using TangentMatrix = std::array<std::array<double, tangent_dimension>, tangent_dimension>;
using TangentVector = std::array<double, tangent_dimension>;

// The linearisation of one event's transition x⁺ = g(x⁻, t).
struct ResetJacobian {
  TangentMatrix state{};  // ∂g/∂x on (q, q̇)
  TangentVector time{};   // ∂g/∂t (the reset's explicit time dependence: a moving table)
  // The state after the event does not depend on the state before it: an
  // accumulation of impacts ending at rest on a wall, a release at a time set
  // by the forcing alone. Nearby states merge, so the saltation matrix is zero.
  bool collapses = false;
};

// The resets every impact oscillator here is made of:
// a grazing touch (or a run stopped at the event) leaves the state alone;
inline ResetJacobian identity_reset() {
  ResetJacobian reset;
  reset.state = {{{1.0, 0.0}, {0.0, 1.0}}};
  return reset;
}
// an accumulation or a release at a time set by the forcing merges nearby states;
inline ResetJacobian collapsed_reset() {
  ResetJacobian reset;
  reset.collapses = true;
  return reset;
}
// an impact that puts q on the constraint and sets q̇⁺ = −r q̇⁻ (+ terms in t
// alone): ∂g/∂x = [[0, 0], [0, −r]].
inline ResetJacobian restitution_reset(double restitution) {
  ResetJacobian reset;
  reset.state = {{{0.0, 0.0}, {0.0, -restitution}}};
  return reset;
}

template <class S>
concept HasJacobian = HybridSystem<S> &&
    requires(const S& system, typename S::Mode mode, std::size_t k, const typename S::State& x,
             double t, TangentMatrix& jacobian, CrossingKind crossing,
             const Transition<typename S::State, typename S::Mode>& after) {
      // ∂f/∂x of the mode's vector field on (q, q̇)
      { system.jacobian(mode, x, t, jacobian) };
      // ∂h/∂x of witness k on (q, q̇); its ∂h/∂t is WitnessSample::rate − ∂h/∂x · f
      { system.witness_gradient(mode, k, x, t) } -> std::same_as<TangentVector>;
      // the linearisation of the transition that on_event returned as `after`
      { system.reset_jacobian(mode, k, crossing, x, t, after) } -> std::same_as<ResetJacobian>;
      // whether the mode pins the state to a constraint (resting on a wall or
      // table): nearby states in it are the same state, tangent vectors are zero
      { system.pinned(mode) } -> std::convertible_to<bool>;
    };

}  // namespace impactlab
