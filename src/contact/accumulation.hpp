// Accumulation of impacts (chattering, Zeno behaviour): the named guard that
// turns an infinite sequence of ever smaller impacts into one event.
//
// After an impact with restitution r the contact separates at normal speed u
// while a normal acceleration a > 0 pushes it back. With a constant, the
// flight times form a geometric series 2u/a, 2ru/a, 2r²u/a, ... whose sum
//     t_rem = 2u / (a (1 - r))
// is the time left until the impacts accumulate (Budd & Dux 1994; Nordmark &
// Piiroinen 2009 use the same limit). The estimate is accepted where the
// acceleration is nearly constant over that time, by its Taylor bound
// |ȧ| t_rem + ½ |ä| t_rem² <= tolerance · a (its relative error is then about
// the tolerance; the second-order term matters where ȧ passes through zero,
// once per forcing period, and a first-order test alone would accept a t_rem
// of seconds there), or where the remaining time is itself negligible,
// t_rem <= tolerance · time_scale; otherwise the next impact is simulated and
// the test repeated with its smaller u.
#pragma once

#include <cmath>
#include <optional>

namespace impactlab {

struct ChatterProbe {
  double separation_speed;      // u >= 0, normal speed just after the impact (m/s)
  double approach_acceleration; // a, normal acceleration towards the wall (m/s²)
  double acceleration_rate;     // ȧ (m/s³)
  double restitution;           // r in [0, 1]
  double acceleration_curvature;  // ä (m/s⁴)
};

// Time until the accumulation point (s), or nothing when the sequence does
// not converge (a <= 0, r >= 1) or the constant-acceleration estimate is not
// yet accurate to `tolerance`.
// time_scale: the system's characteristic time (s), for example 1/ω.
inline std::optional<double> time_to_accumulation(const ChatterProbe& probe, double tolerance,
                                                  double time_scale) {
  if (!(probe.approach_acceleration > 0.0) || !(probe.restitution < 1.0)) return std::nullopt;
  const double remaining = 2.0 * probe.separation_speed /
                           (probe.approach_acceleration * (1.0 - probe.restitution));
  const double drift = std::fabs(probe.acceleration_rate) * remaining +
                       0.5 * std::fabs(probe.acceleration_curvature) * remaining * remaining;
  if (drift <= tolerance * probe.approach_acceleration || remaining <= tolerance * time_scale)
    return remaining;
  return std::nullopt;
}

}  // namespace impactlab
