// The collision matrix K: how an impulse J at a contact changes the relative
// contact velocity, Δu = K J (docs/rigidbody.md).
//
// Two free bodies A and B touching at world offsets r_A, r_B from their
// centres, J applied to A and −J to B, u = u_A − u_B:
//     3D  K = (1/m_A + 1/m_B) I − r̃_A I_A⁻¹ r̃_A − r̃_B I_B⁻¹ r̃_B
//     2D  K = (1/m_A + 1/m_B) I + r_A⊥ r_A⊥ᵀ / I_A + r_B⊥ r_B⊥ᵀ / I_B
// Generalized coordinates (M q̈ = h + Wᵀ λ, contact velocities u = W q̇ + w):
//         K = W M⁻¹ Wᵀ, symmetric positive semi-definite; it is singular when
//         the contact has more directions than the system has degrees of
//         freedom (the 1-DOF pendulum: rank one). M⁻¹ is applied by a
//         Cholesky solve, never formed; K itself is never inverted here.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <impactlab/rigidbody/body2d.hpp>
#include <impactlab/rigidbody/body3d.hpp>
#include <impactlab/rigidbody/cross_matrix.hpp>

namespace impactlab::rigidbody {

inline Eigen::Matrix3d collision_matrix(const Body3D& a, const Eigen::Vector3d& r_a,
                                        const Body3D& b, const Eigen::Vector3d& r_b) {
  const Eigen::Matrix3d ra = cross_matrix(r_a);
  const Eigen::Matrix3d rb = cross_matrix(r_b);
  Eigen::Matrix3d k = (a.inverse_mass + b.inverse_mass) * Eigen::Matrix3d::Identity();
  k -= ra * a.inverse_inertia_world() * ra;
  k -= rb * b.inverse_inertia_world() * rb;
  return k;
}

inline Eigen::Matrix2d collision_matrix(const Body2D& a, const Eigen::Vector2d& r_a,
                                        const Body2D& b, const Eigen::Vector2d& r_b) {
  const Eigen::Vector2d pa = perpendicular(r_a);
  const Eigen::Vector2d pb = perpendicular(r_b);
  Eigen::Matrix2d k = (a.inverse_mass + b.inverse_mass) * Eigen::Matrix2d::Identity();
  k += a.inverse_inertia * pa * pa.transpose();
  k += b.inverse_inertia * pb * pb.transpose();
  return k;
}

// K = W M⁻¹ Wᵀ for a D-row contact Jacobian W (D × N) and mass matrix M (N × N, SPD)
template <int D, int N>
Eigen::Matrix<double, D, D> collision_matrix(const Eigen::Matrix<double, N, N>& mass,
                                             const Eigen::Matrix<double, D, N>& jacobian) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> cholesky(mass);
  const Eigen::Matrix<double, N, D> m_inv_wt = cholesky.solve(jacobian.transpose());
  return jacobian * m_inv_wt;
}

}  // namespace impactlab::rigidbody
