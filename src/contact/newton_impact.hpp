// Newton's kinematic impact law for a one-degree-of-freedom contact with
// Coulomb friction (Model N, docs/simulation.md).
//
// With one degree of freedom q and a wall whose normal contact velocity is
// γ_N = W_N q̇, Newton's law γ_N⁺ = -e_n γ_N⁻ fixes q̇⁺ = -e_n q̇⁻ whatever the
// friction; friction only decides how the impulse splits into a normal part
// P_N and a tangential part P_T = -s μ P_N, s = sgn(γ_T⁻):
//     M (q̇⁺ - q̇⁻) = (W_N - s μ W_T) P_N
// Valid for e_n in [0, 1], μ >= 0. The split needs D = W_N - s μ W_T of the
// sign of W_N; otherwise the configuration is a Painlevé one (painleve.hpp).
// Reference: Pfeiffer & Glocker, Multibody Dynamics with Unilateral Contacts
// (1996), ch. 7; Brogliato, Nonsmooth Mechanics (2016), §4.
#pragma once

#include <cmath>

namespace impactlab {

struct NewtonImpactResult {
  double qdot_after;      // q̇⁺
  double normal_impulse;  // P_N (N s), meaningful only when consistent
  double denominator;     // (W_N - s μ W_T) / W_N: positive when consistent
};

// mass: generalized mass M (kg m² for an angle); w_n, w_t: normal and
// tangential Jacobians (m per unit of q); gamma_t: tangential velocity before
// the impact (m/s).
inline NewtonImpactResult newton_impact(double qdot_before, double mass, double w_n, double w_t,
                                        double gamma_t, double e_n, double mu) {
  const double s = gamma_t > 0.0 ? 1.0 : gamma_t < 0.0 ? -1.0 : 0.0;
  const double qdot_after = -e_n * qdot_before;
  const double effective = w_n - s * mu * w_t;
  const double impulse = mass * (qdot_after - qdot_before) / effective;
  return {qdot_after, impulse, effective / w_n};
}

}  // namespace impactlab
