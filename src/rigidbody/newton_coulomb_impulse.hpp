// The Newton–Coulomb impulse at one contact (docs/rigidbody.md): a pure function of the collision matrix K, the relative
// contact velocity before the impact u⁻ and the contact normal n.
//
//   approach      u_n⁻ = n·u⁻ < 0 (otherwise no impulse: the contact separates)
//   stick         u⁺ = −e_n u_n⁻ n − e_t u_t⁻, J = K⁻¹ (u⁺ − u⁻),
//                 accepted if J_n ≥ 0 and |J_t| ≤ μ J_n
//   slide         J = j (n − μ t), t the unit sliding direction,
//                 j = −(1 + e_n) u_n⁻ / nᵀK(n − μ t)
//
// Coefficients: e_n ∈ [0, 1] normal restitution (Newton), μ ≥ 0 Coulomb
// friction, e_t ∈ [−1, 1] an optional tangential restitution used only in the
// stick case (0: the contact point stops sliding, the default of the lecture;
// positive: the slip reverses, as for a superball; negative: a part −e_t of
// the slip is kept, the convention of the pendulum paper's e_y).
// Sliding direction: t = u_t⁻/|u_t⁻|; where u_t⁻ = 0 and sticking is not
// possible, the direction in which the normal impulse alone drives the slip,
// t ∝ (K n)_t (friction opposes the slip it would start).
//
// Singular K (more contact directions than degrees of freedom, such as the
// 1-DOF pendulum): never inverted blindly. The stick equations K J = Δu are
// solved with a complete orthogonal decomposition; if Δu is not in the range
// of K (to round-off), sticking is impossible and the impact slides. When it
// is, the minimum-norm J is taken: every J of the affine solution set gives
// the same Δu, so the velocities after the impact do not depend on the choice.
// A slide with nᵀK(n − μ t) ≤ 0 (a frictional impact that would pull the
// bodies together, the impulsive Painlevé case) returns `inconsistent` and a
// zero impulse rather than dividing by ~0.
//
// References: Mirtich, Impulse-based Dynamic Simulation of Rigid Body Systems
// (1996), ch. 4; Stronge, Impact Mechanics (2000), ch. 4 (Newton's law with
// friction and its energy caveats for non-collinear impacts); the TDBD24
// lecture in ../shared/seeds/newton-coulomb-impulse-lecture.txt.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include <impactlab/rigidbody/minimum_norm_solution.hpp>

namespace impactlab::rigidbody {

enum class ImpulseRegime {
  separating,    // u_n⁻ ≥ 0: no impulse
  stick,         // the contact point's tangential velocity is set by e_t
  slide,         // friction on the cone boundary, J = j (n − μ t)
  inconsistent,  // sliding impulse with nᵀK(n − μ t) ≤ 0: no admissible impulse
};

struct ImpactCoefficients {
  double e_n = 0.0;  // normal restitution, [0, 1]
  double mu = 0.0;   // Coulomb friction, >= 0
  double e_t = 0.0;  // tangential restitution in the stick case, [−1, 1]
};

template <int D>
struct NewtonCoulombImpulse {
  using Vector = Eigen::Matrix<double, D, 1>;
  Vector impulse = Vector::Zero();         // J (N s, or generalized units of K⁻¹ u)
  Vector velocity_after = Vector::Zero();  // u⁺ = u⁻ + K J (m/s)
  double normal_impulse = 0.0;             // J_n = n·J
  double slide_denominator = 0.0;          // nᵀK(n − μ t) in the slide case, else 0
  ImpulseRegime regime = ImpulseRegime::separating;
};

// K: collision matrix (D × D, symmetric positive semi-definite); u_before:
// relative contact velocity u⁻; normal: unit contact normal n (separation
// positive along it).
template <int D>
NewtonCoulombImpulse<D> newton_coulomb_impulse(const Eigen::Matrix<double, D, D>& K,
                                               const Eigen::Matrix<double, D, 1>& u_before,
                                               const Eigen::Matrix<double, D, 1>& normal,
                                               const ImpactCoefficients& c) {
  using Vector = Eigen::Matrix<double, D, 1>;
  NewtonCoulombImpulse<D> out;
  out.velocity_after = u_before;
  const double u_n = normal.dot(u_before);
  if (!(u_n < 0.0)) return out;
  const Vector u_t = u_before - u_n * normal;

  // stick: J from K J = Δu, in the range of K only
  const Vector target = -c.e_n * u_n * normal - c.e_t * u_t;
  const Vector delta = target - u_before;
  const Vector stick = minimum_norm_solution(K, delta);
  const double scale = K.norm() * stick.norm() + delta.norm();
  const bool reachable = (K * stick - delta).norm() <= 1e-12 * scale;
  const double stick_n = normal.dot(stick);
  const Vector stick_t = stick - stick_n * normal;
  if (reachable && stick_n >= 0.0 && stick_t.norm() <= c.mu * stick_n * (1.0 + 1e-12)) {
    out.impulse = stick;
    out.normal_impulse = stick_n;
    out.velocity_after = u_before + K * stick;
    out.regime = ImpulseRegime::stick;
    return out;
  }

  // slide: friction on the cone boundary, opposing the slip
  Vector slip = u_t;
  if (slip.norm() == 0.0) {
    const Vector kn = K * normal;
    slip = kn - normal.dot(kn) * normal;
  }
  const double slip_norm = slip.norm();
  const Vector t = slip_norm > 0.0 ? Vector(slip / slip_norm) : Vector::Zero();
  const Vector direction = normal - c.mu * t;
  out.slide_denominator = normal.dot(K * direction);
  // relative to the frictionless nᵀKn: a denominator this small turns
  // round-off into an arbitrarily large impulse
  if (!(out.slide_denominator > 1e-9 * normal.dot(K * normal))) {
    out.regime = ImpulseRegime::inconsistent;
    return out;
  }
  const double j = -(1.0 + c.e_n) * u_n / out.slide_denominator;
  out.impulse = j * direction;
  out.normal_impulse = j;
  out.velocity_after = u_before + K * out.impulse;
  out.regime = ImpulseRegime::slide;
  return out;
}

}  // namespace impactlab::rigidbody
