// One unilateral frictional contact of a system in generalized coordinates
// (Euler–Lagrange; Lagrange and multibody lectures in ../shared/seeds/):
//     M(q) q̈ + c(q, q̇, t) = τ + W_Nᵀ λ_N + W_Tᵀ λ_T
// with the contact's normal and tangential velocities
//     γ = (γ_N, γ_T) = W q̇ + w(q, t),     γ̇ = W q̈ + ŵ(q, q̇, t)
// W = [W_N; W_T] (2 × N) the contact Jacobian, w the part of the contact
// velocity not due to q̇ (a driven pivot), ŵ the acceleration drift
// (Ẇ q̇ + ẇ). A system such as the pendulum with a driven pivot fills one
// of these per contact and per state; the impulse law (newton_coulomb_impulse.hpp)
// and the contact phase (contact_phase.hpp) work on it.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <impactlab/rigidbody/collision_matrix.hpp>
#include <impactlab/rigidbody/newton_coulomb_impulse.hpp>

namespace impactlab::rigidbody {

template <int N>
struct GeneralizedContact {
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  Matrix mass = Matrix::Identity();                    // M(q), SPD (kg, kg m², ...)
  Vector forces = Vector::Zero();                      // h = τ − c(q, q̇, t) (N, N m)
  Eigen::Matrix<double, 2, N> jacobian = Eigen::Matrix<double, 2, N>::Zero();  // rows W_N, W_T
  Eigen::Vector2d velocity_offset = Eigen::Vector2d::Zero();     // w (m/s)
  Eigen::Vector2d acceleration_drift = Eigen::Vector2d::Zero();  // ŵ (m/s²)

  // γ = W q̇ + w (m/s)
  [[nodiscard]] Eigen::Vector2d contact_velocity(const Vector& qdot) const {
    return jacobian * qdot + velocity_offset;
  }
  // q̈ = M⁻¹ (h + Wᵀ λ) for contact forces λ = (λ_N, λ_T) (N)
  [[nodiscard]] Vector acceleration(const Eigen::Vector2d& lambda) const {
    return Eigen::LLT<Matrix>(mass).solve(forces + jacobian.transpose() * lambda);
  }
  // Δq̇ = M⁻¹ Wᵀ P for a contact impulse P = (P_N, P_T) (N s)
  [[nodiscard]] Vector velocity_jump(const Eigen::Vector2d& impulse) const {
    return Eigen::LLT<Matrix>(mass).solve(jacobian.transpose() * impulse);
  }
  // K = W M⁻¹ Wᵀ (2 × 2, rank ≤ N)
  [[nodiscard]] Eigen::Matrix2d collision_matrix() const {
    return rigidbody::collision_matrix<2, N>(mass, jacobian);
  }
};

// The result of an impact at a generalized contact.
template <int N>
struct GeneralizedImpact {
  Eigen::Matrix<double, N, 1> qdot_after;
  NewtonCoulombImpulse<2> impulse;  // in contact coordinates (normal, tangent)
};

// The Newton–Coulomb impulse in contact coordinates, n = (1, 0), and the
// generalized velocities after it.
template <int N>
GeneralizedImpact<N> generalized_impact(const GeneralizedContact<N>& contact,
                                        const Eigen::Matrix<double, N, 1>& qdot_before,
                                        const ImpactCoefficients& coefficients) {
  const auto impulse = newton_coulomb_impulse<2>(contact.collision_matrix(),
                                                 contact.contact_velocity(qdot_before),
                                                 Eigen::Vector2d::UnitX(), coefficients);
  return {qdot_before + contact.velocity_jump(impulse.impulse), impulse};
}

}  // namespace impactlab::rigidbody
