// Accumulation of impacts (chattering, Zeno behaviour): the named guard that
// turns an infinite sequence of ever smaller impacts into one event.
//
// Local model. Near the wall the normal gap z >= 0 obeys
//     z̈ = −a(t) − c ż + κ z,   a(t) = a + ȧ s + ½ ä s² + ...   (s from the impact)
// with a > 0 the normal acceleration towards the wall, c a viscous damping
// rate (1/s) and κ the change of that acceleration with the gap (1/s²). After
// an impact the contact separates at normal speed u and every impact returns
// it with restitution r.
//
// Estimate. With a constant (ȧ = ä = c = κ = 0) the flight times form the
// geometric series 2u/a, 2ru/a, ... whose sum
//     T0 = 2u / (a (1 − r))
// is the time left until the impacts accumulate (Budd & Dux 1994; Nordmark &
// Piiroinen 2009). To first order in ȧ and c a flight of nominal length
// τ = 2u/a is shorter by ȧ τ²/(3a) + c τ²/6, returns with its speed raised by
// ȧ τ²/6 and lowered by c u τ/3, and later flights see a(t) drifted by ȧ s;
// summing these geometric series over all flights gives a closed form, the
// same for every r,
//     T = T0 − (T0² / 3) (ȧ / a + c / 2).
// Its error is second order in the flight times. Measured on the model
// integrated to round-off for r in [0, 0.9] (docs/simulation.md), the
// coefficients of the remainder are at most 0.26 (ȧ/a)² T0³,
// 0.06 c² T0³, 0.11 |ä|/a T0³ and 0.09 |κ| T0³; the bound used here takes
// about twice each,
//     E = T0³ [ ½ (|ȧ|/a + c/2)² + ¼ |ä|/a + ⅕ |κ| ].
//
// Acceptance. The estimate is taken when E is within the accepted error of
// the accumulation time (the scene's `accumulation_tol` times its time scale;
// by default the integrator's rtol), with the first-order term small
// (|T − T0| <= 0.1 T0, inside the asymptotic regime); or, whatever E, when
// the chatter is below what the event loop can resolve: the next flight's
// apex u²/(2a) within the integrator's accuracy on the gap; or when the next
// impact could not be timed better than E anyway: its time is known to the
// round-off of the gap over its speed, ρ/u (ρ a few ulps of the wall's
// coordinate), and crawling on would add that error instead of removing E.
// Otherwise the next impact is simulated and the test repeated with its
// smaller u: E falls like u³, so a few impacts reach any tolerance.
//
// Round-off. Where the estimate is taken because the chatter is below the
// event loop's resolution, the impacts before it carry their own round-off:
// each is timed to ρ/u_k, and a timing error δ of one impact changes the next
// speed by a δ and so the time left by 2δ/(1 − r). Over the geometric chatter
// (Σ ρ/u_k ≤ ρ/(u (1 − r))) the bound reported then is
//     E + 2ρ / (u (1 − r)²),
// the floor no tolerance can go below in double precision.
#pragma once

#include <cmath>
#include <optional>

namespace impactlab {

struct ChatterProbe {
  double separation_speed;        // u >= 0, normal speed just after the impact (m/s)
  double approach_acceleration;   // a, normal acceleration towards the wall (m/s²)
  double acceleration_rate;       // ȧ (m/s³)
  double restitution;             // r in [0, 1]
  double acceleration_curvature;  // ä (m/s⁴)
  double damping = 0.0;           // c: the normal acceleration gets −c ż (1/s)
  double gap_stiffness = 0.0;     // κ: the normal acceleration gets +κ z (1/s²)
};

// What the accumulation estimate is held to.
struct AccumulationTolerance {
  double time = 1e-12;  // accepted error bound of the accumulation time (s)
  // apex height of a flight (in the units of u times time) at or below which
  // the event loop cannot resolve the chatter any more: the estimate is taken
  double unresolved_apex = 1e-14;
  // ρ, the round-off of the gap where it is computed (units of u times time)
  double gap_roundoff = 1e-17;
};

struct AccumulationEstimate {
  double remaining;    // time from the impact to the accumulation point (s)
  double error_bound;  // E, the bound on the error of `remaining` (s)
};

// The first-order time left, T = T0 − (T0² / 3)(ȧ / a + c / 2) with
// T0 = 2u / (a (1 − r)), over a number type: a dual number run through it
// gives the accumulation time's derivatives (the saltation of a jump to an
// accumulation point, oscillators/pendulum_walls/rigid_pendulum_spin.hpp).
template <class Number>
Number accumulation_time(const Number& separation_speed, const Number& approach_acceleration,
                         const Number& acceleration_rate, double restitution, double damping) {
  const Number t0 = 2.0 * separation_speed / (approach_acceleration * (1.0 - restitution));
  const Number drift = acceleration_rate / approach_acceleration + 0.5 * damping;
  return t0 - t0 * t0 * drift / 3.0;
}

// The first-order estimate and its error bound, or nothing when the sequence
// does not converge (a <= 0, r >= 1).
inline std::optional<AccumulationEstimate> estimate_accumulation(const ChatterProbe& probe) {
  const double a = probe.approach_acceleration;
  const double r = probe.restitution;
  if (!(a > 0.0) || !(r < 1.0)) return std::nullopt;
  const double t0 = 2.0 * probe.separation_speed / (a * (1.0 - r));
  const double drift_size = std::fabs(probe.acceleration_rate) / a + 0.5 * std::fabs(probe.damping);
  const double second_order = 0.5 * drift_size * drift_size +
                              0.25 * std::fabs(probe.acceleration_curvature) / a +
                              0.2 * std::fabs(probe.gap_stiffness);
  return AccumulationEstimate{accumulation_time(probe.separation_speed, a, probe.acceleration_rate,
                                                r, probe.damping),
                              t0 * t0 * t0 * second_order};
}

// The estimate when it is accepted (see the header comment), else nothing:
// simulate the next impact.
inline std::optional<AccumulationEstimate> accept_accumulation(const ChatterProbe& probe,
                                                               const AccumulationTolerance& tol) {
  const auto estimate = estimate_accumulation(probe);
  if (!estimate) return std::nullopt;
  const double a = probe.approach_acceleration;
  const double u = probe.separation_speed;
  const double t0 = 2.0 * u / (a * (1.0 - probe.restitution));
  const bool asymptotic = std::fabs(estimate->remaining - t0) <= 0.1 * t0;
  const bool accurate = asymptotic && estimate->error_bound <= tol.time;
  const bool unresolvable = u * u / (2.0 * a) <= tol.unresolved_apex ||
                            estimate->error_bound * u <= tol.gap_roundoff;
  if (accurate) return estimate;
  if (!unresolvable) return std::nullopt;
  const double one_minus_r = 1.0 - probe.restitution;
  return AccumulationEstimate{
      estimate->remaining,
      estimate->error_bound + 2.0 * tol.gap_roundoff / (u * one_minus_r * one_minus_r)};
}

}  // namespace impactlab
