// The sliding-impact conditions of Jin, Hu & Bishop (2003), Sec. 4, for the
// pendulum between walls (Model P). Pure functions of the
// velocities at the instant of impact; docs/model-card.md gives each
// equation, its garbled source text and the reading chosen.
//
// Velocities at an impact with either wall (the walls are mirror images):
//     v_n  = l cos θ0 |θ̇0|            normal approach speed (m/s), > 0
//     v_y0 = V0 sin ωt0 − l sin θ θ̇0   tangential velocity, y down (m/s)
// With one degree of freedom every velocity jump obeys Δv_y = −tan θ0 Δv_n
// (the paper's Eq. 25). Newton's law Δv_n = −(1 + e_n) v_n and the paper's
// tangential law Δv_y = −(1 + e_y) v_y0 hold together only when
//     (1 + e_n) tan θ0 v_n + (1 + e_y) v_y0 = 0          (Eq. 26)
// and then the impact is instantaneous; otherwise it is a sliding impact that
// lasts until the normal force vanishes, g − V0 ω cos ωt_f = 0 (Eq. 20), and
// the paper's tangential law at its end, −e_y v_y0 = V0 sin ωt_f (Eq. 21),
// holds only when (e_y v_y0)² = V0² − (g/ω)² (Eq. 22).
#pragma once

#include <cmath>
#include <limits>

namespace impactlab {

// Relative tolerance of the Eq. 26 equality, against |v_n| + |v_y0|: the
// equality is a measure-zero condition, met only to round-off.
inline constexpr double instantaneous_impact_tolerance = 1e-9;

// Left side of Eq. 26 (m/s): zero when Newton's normal law and the
// tangential restitution law can both hold in an instantaneous impact.
inline double instantaneous_impact_residual(double normal_speed, double tangential_velocity,
                                            double e_n, double e_t, double tan_theta0) {
  return (1.0 + e_n) * tan_theta0 * normal_speed + (1.0 + e_t) * tangential_velocity;
}

// The paper's test for an instantaneous impact (Eq. 25 with Eq. 26). e_t = −1
// is the paper's "no tangential effects": no tangential law is imposed, so
// every impact is instantaneous (docs/model-card.md).
inline bool is_instantaneous_impact(double normal_speed, double tangential_velocity, double e_n,
                                    double e_t, double tan_theta0) {
  if (e_t == -1.0) return true;
  const double residual =
      instantaneous_impact_residual(normal_speed, tangential_velocity, e_n, e_t, tan_theta0);
  return std::fabs(residual) <=
         instantaneous_impact_tolerance * (std::fabs(normal_speed) + std::fabs(tangential_velocity));
}

// Tangential velocity of a bob resting on a wall when the slip ends at the
// normal force's zero (Eqs. 20, 21): V0 sin ωt_f with g = V0 ω cos ωt_f and
// g_e rising (sin ωt_f > 0), i.e. +sqrt(V0² − (g/ω)²) (m/s). NaN when
// V0 ω < g: g_e never vanishes and no slip can end that way.
inline double slip_end_velocity(double V0, double omega, double g) {
  const double squared = V0 * V0 - (g / omega) * (g / omega);
  return squared >= 0.0 ? std::sqrt(squared) : std::numeric_limits<double>::quiet_NaN();
}

// The sliding-impact residual of Eqs. 21–22 (m/s), the paper's Fig. 4
// "v_c0 − v_y0": V0 sin ωt_f − (−e_y v_y0). Zero when a sliding impact with
// tangential velocity v_y0 ends with the paper's tangential restitution;
// NaN when V0 ω < g.
inline double sliding_condition_residual(double V0, double omega, double g, double e_t,
                                         double tangential_velocity) {
  return slip_end_velocity(V0, omega, g) + e_t * tangential_velocity;
}

// Model P's extension of the record of an impact (the core's record,
// core/event_log.hpp, holds what every model computes): the residuals of its
// impact conditions (m/s), NaN where not computed (another event, another
// model). PaperPendulumWalls::impact_residuals fills it.
struct PaperImpactResiduals {
  double instantaneous = std::numeric_limits<double>::quiet_NaN();  // Eq. 26
  double sliding = std::numeric_limits<double>::quiet_NaN();        // Eqs. 21-22 (Fig. 4)
};

}  // namespace impactlab
