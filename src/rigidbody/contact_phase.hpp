// A persistent unilateral contact resolved at acceleration level
// (docs/rigidbody.md; Pfeiffer & Glocker, Multibody Dynamics with Unilateral Contacts (1996),
// ch. 6–7): given the state, find the contact forces λ = (λ_N, λ_T) with
//     γ̈_N = a_N + (G λ)_N ≥ 0,   λ_N ≥ 0,   γ̈_N λ_N = 0      (Signorini)
//     sliding (γ_T ≠ 0):  λ_T = −μ s λ_N, s = sgn γ_T          (Coulomb)
//     sticking (γ_T = 0): |λ_T| ≤ μ λ_N and γ̈_T = 0, or slip starting in
//                         the direction s with λ_T = −μ s λ_N, s γ̈_T > 0
// where a = W M⁻¹ h + ŵ are the contact accelerations without contact forces
// and G = W M⁻¹ Wᵀ (generalized_system.hpp). This is a small linear
// complementarity problem; it is solved by enumerating its cases.
//
// Painlevé: when sliding, λ_N = −a_N / A with A = G_NN − μ s G_NT. A > 0:
// one solution, λ_N = max(0, −a_N / A). A ≤ 0 (possible only for μ above a
// critical value fixed by the geometry, e.g. 4/3 for the classic rod): if
// a_N < 0 there is no solution, if a_N ≥ 0 there are two (λ_N = 0 and
// −a_N / A). Both are returned as typed regimes, never divided through
// (Painlevé 1895; Stewart, SIAM Review 42 (2000) 3–39).
#pragma once

#include <cmath>

#include <Eigen/Core>

#include <impactlab/rigidbody/generalized_system.hpp>
#include <impactlab/rigidbody/minimum_norm_solution.hpp>

namespace impactlab::rigidbody {

enum class ContactRegime {
  detached,              // λ = 0 and γ̈_N ≥ 0: the contact releases
  slide,                 // λ_N > 0, λ_T = −μ s λ_N
  stick,                 // λ_N > 0, |λ_T| ≤ μ λ_N, γ̈_T = 0
  painleve_no_solution,  // no force satisfies the contact laws
  painleve_ambiguous,    // several do
};

struct ContactForces {
  double normal = 0.0;      // λ_N (N)
  double tangential = 0.0;  // λ_T (N)
  double slip_sign = 0.0;   // s of the slide in force (0 when sticking or detached)
  double denominator = 0.0; // A = G_NN − μ s G_NT of the slide case, scaled by 1/G_NN
  ContactRegime regime = ContactRegime::detached;
};

namespace detail {

// A = G_NN − μ s G_NT relative to G_NN: ≤ this margin is a Painlevé case
inline constexpr double painleve_margin = 1e-9;

inline ContactForces sliding_forces(const Eigen::Matrix2d& G, const Eigen::Vector2d& a, double mu,
                                    double s) {
  ContactForces out;
  out.slip_sign = s;
  out.denominator = (G(0, 0) - mu * s * G(0, 1)) / G(0, 0);
  if (out.denominator > painleve_margin) {
    const double lambda = std::max(0.0, -a(0) / (G(0, 0) * out.denominator));
    out.normal = lambda;
    out.tangential = -mu * s * lambda;
    out.regime = lambda > 0.0 ? ContactRegime::slide : ContactRegime::detached;
    return out;
  }
  out.regime = a(0) < 0.0 ? ContactRegime::painleve_no_solution : ContactRegime::painleve_ambiguous;
  return out;
}

}  // namespace detail

// slip_velocity: γ_T (m/s); it is treated as zero (a sticking contact, or a
// slide about to stop) when |γ_T| ≤ stick_tolerance.
template <int N>
ContactForces contact_forces(const GeneralizedContact<N>& contact, double mu, double slip_velocity,
                             double stick_tolerance) {
  const Eigen::Matrix2d G = contact.collision_matrix();
  const Eigen::Vector2d a =
      contact.jacobian * Eigen::LLT<Eigen::Matrix<double, N, N>>(contact.mass).solve(contact.forces) +
      contact.acceleration_drift;

  if (std::fabs(slip_velocity) > stick_tolerance)
    return detail::sliding_forces(G, a, mu, slip_velocity > 0.0 ? 1.0 : -1.0);

  // γ_T = 0: enumerate detached, stick, slide in either direction
  int solutions = 0;
  ContactForces found;
  if (a(0) >= 0.0) {
    ++solutions;
    found = ContactForces{};
  }
  const Eigen::Vector2d stick = minimum_norm_solution(G, Eigen::Vector2d(-a));
  const bool reachable = (G * stick + a).norm() <= 1e-12 * (G.norm() * stick.norm() + a.norm());
  if (reachable && stick(0) > 0.0 && std::fabs(stick(1)) <= mu * stick(0)) {
    ++solutions;
    found = ContactForces{stick(0), stick(1), 0.0, 1.0, ContactRegime::stick};
  }
  for (const double s : {1.0, -1.0}) {
    const double denominator = G(0, 0) - mu * s * G(0, 1);
    if (std::fabs(denominator) <= detail::painleve_margin * G(0, 0)) continue;
    const double lambda = -a(0) / denominator;
    if (!(lambda > 0.0)) continue;
    const double slip_acceleration = a(1) + (G(1, 0) - mu * s * G(1, 1)) * lambda;
    if (!(s * slip_acceleration > 0.0)) continue;
    ++solutions;
    found = ContactForces{lambda, -mu * s * lambda, s, denominator / G(0, 0),
                          ContactRegime::slide};
  }
  if (solutions == 1) return found;
  ContactForces painleve;
  painleve.regime =
      solutions == 0 ? ContactRegime::painleve_no_solution : ContactRegime::painleve_ambiguous;
  return painleve;
}

}  // namespace impactlab::rigidbody
