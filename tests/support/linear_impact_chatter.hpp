// Test support: the chatter of the linear impact oscillator
// ẍ + 2ζẋ + x = A cos ωt against a stop at x = σ (ẋ⁺ = −r ẋ⁻) after a
// release, followed impact by impact on the closed-form flight in long
// double, independently of the toolkit's integrators and event location.
//
// The mass rests on the stop while the push A cos ωt − σ is positive and is
// released where it falls through zero, ω t_r = arccos(σ/A). It flies from
// (σ, 0), returns to the stop and chatters in the next interval where the
// push is positive, before t_r + T. Each landing is the first zero of the
// gap σ − x after the last impact; each flight starts on the stop, so the
// gap is −(x(t) − x(t_k)), computed term by term from differences. It is
// sampled in steps of a sixteenth of the hop's length under the push at
// the impact (of a 4000th of the period for the first return), then
// bisected to the last bit of long double. The chatter is classified by
// where it goes (analysis/chatter_onset.hpp's local model):
// u = v/(c s²) (v the rebound speed, s the time left to t_r + T,
// c = Aω sin ωt_r the push's rate of fall there) drifting below a quarter
// of the self-similar u* means it accumulates; u > 3/8 (no landing left
// before t_r + T in the local model) or a landing after t_r + T means it
// escapes. The onset of complete chatter of ζ = 0.05, A = 1, σ = 0.5,
// r = 0.5 found by bisection on this class agrees with the same computation
// in 40-digit arithmetic (mpmath) to 2e-17 in ω.
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace impactlab::testing {

struct ChatterParameters {
  long double zeta = 0.05L, amplitude = 1.0L, sigma = 0.5L, restitution = 0.5L;
};

// The closed-form flight from (x0, v0) at t0.
class ChatterFlight {
 public:
  ChatterFlight(const ChatterParameters& p, long double omega, long double t0, long double x0,
                long double v0)
      : zeta_(p.zeta), omega_(omega), t0_(t0) {
    const long double detuning = 1.0L - omega * omega;
    const long double denominator = detuning * detuning + 4.0L * p.zeta * p.zeta * omega * omega;
    P_ = p.amplitude * detuning / denominator;
    Q_ = 2.0L * p.zeta * omega * p.amplitude / denominator;
    wd_ = std::sqrt(1.0L - p.zeta * p.zeta);
    c1_ = x0 - (P_ * std::cos(omega * t0) + Q_ * std::sin(omega * t0));
    const long double vp = omega * (Q_ * std::cos(omega * t0) - P_ * std::sin(omega * t0));
    c2_ = (v0 - vp + p.zeta * c1_) / wd_;
  }
  // x(t) − x(t0), from differences of each term (no cancellation between
  // x(t) and x(t0): a hop 1e-6 long is timed to 1e-19 of its own length)
  [[nodiscard]] long double displacement(long double t) const {
    const long double tau = t - t0_;
    const long double half = std::sin(0.5L * omega_ * tau);
    const long double middle = 0.5L * omega_ * (t + t0_);
    const long double particular =
        2.0L * half * (Q_ * std::cos(middle) - P_ * std::sin(middle));
    const long double c = std::cos(wd_ * tau), s = std::sin(wd_ * tau);
    const long double half_wd = std::sin(0.5L * wd_ * tau);
    const long double decay_minus_one = std::expm1(-zeta_ * tau);
    const long double homogeneous = c1_ * (decay_minus_one * c - 2.0L * half_wd * half_wd) +
                                    c2_ * (decay_minus_one + 1.0L) * s;
    return particular + homogeneous;
  }
  // {x, ẋ} at t
  [[nodiscard]] std::array<long double, 2> at(long double t) const {
    const long double tau = t - t0_, decay = std::exp(-zeta_ * tau);
    const long double c = std::cos(wd_ * tau), s = std::sin(wd_ * tau);
    return {decay * (c1_ * c + c2_ * s) + P_ * std::cos(omega_ * t) + Q_ * std::sin(omega_ * t),
            decay * ((wd_ * c2_ - zeta_ * c1_) * c - (wd_ * c1_ + zeta_ * c2_) * s) +
                omega_ * (Q_ * std::cos(omega_ * t) - P_ * std::sin(omega_ * t))};
  }

 private:
  long double zeta_, omega_, t0_, P_ = 0, Q_ = 0, wd_ = 0, c1_ = 0, c2_ = 0;
};

// The self-similar chatter's scaled speed u* for restitution r: z* the root
// of (3 − z)(1 − z)² = r (3 − 2z) in (0, 1) by bisection, u* = (3z* − z*²)/6.
inline double self_similar_speed(double r) {
  double low = 0.0, high = 1.0;
  for (int k = 0; k < 200; ++k) {
    const double z = 0.5 * (low + high);
    ((3.0 - z) * (1.0 - z) * (1.0 - z) - r * (3.0 - 2.0 * z) > 0.0 ? low : high) = z;
  }
  const double z = 0.5 * (low + high);
  return (3.0 * z - z * z) / 6.0;
}

struct ChatterImpactRecord {
  long double t;       // the impact's time
  long double speed;   // ẋ⁻ > 0
};

struct ReferenceChatter {
  long double release = 0.0L;       // t_r, the release before the chatter
  long double next_release = 0.0L;  // t_r + T
  std::vector<ChatterImpactRecord> impacts;
  int side = 0;  // +1 it accumulates, −1 it escapes, 0 undecided
};

// The chatter after the release at ω, up to `max_impacts` impacts. It stops
// where the chatter is classified, or with `to_the_end` only at max_impacts
// (or where it escapes).
inline ReferenceChatter reference_chatter(const ChatterParameters& p, long double omega,
                                          int max_impacts, bool to_the_end = false) {
  const long double pi = std::numbers::pi_v<long double>;
  const double u_star = self_similar_speed(static_cast<double>(p.restitution));
  ReferenceChatter chatter;
  chatter.release = std::acos(p.sigma / p.amplitude) / omega;
  chatter.next_release = chatter.release + 2.0L * pi / omega;
  const long double fall_rate = p.amplitude * omega * std::sin(omega * chatter.next_release);
  ChatterFlight flight(p, omega, chatter.release, p.sigma, 0.0L);
  long double step = (chatter.next_release - chatter.release) / 4000.0L;
  long double t = chatter.release + step, limit = chatter.next_release;
  for (int impact = 0; impact < max_impacts; ++impact) {
    while (-flight.displacement(t) > 0.0L) {
      t += step;
      if (t > limit) {
        chatter.side = -1;
        return chatter;
      }
    }
    long double low = t - step, high = t;
    for (int k = 0; k < 200; ++k) {
      const long double middle = 0.5L * (low + high);
      if (!(middle > low && middle < high)) break;
      (-flight.displacement(middle) > 0.0L ? low : high) = middle;
    }
    const long double t_impact = high;
    if (t_impact >= chatter.next_release) {
      chatter.side = -1;
      return chatter;
    }
    const long double speed = flight.at(t_impact)[1];
    chatter.impacts.push_back({t_impact, speed});
    const long double rebound = p.restitution * speed;
    const long double s = chatter.next_release - t_impact;
    const long double u = rebound / (fall_rate * s * s);
    if (impact > 3 && u < 0.25L * u_star) {
      chatter.side = 1;
      if (!to_the_end) return chatter;
    }
    if (impact > 0 && u > 0.375L) {
      chatter.side = -1;
      return chatter;
    }
    flight = ChatterFlight(p, omega, t_impact, p.sigma, -rebound);
    const long double push = p.amplitude * std::cos(omega * t_impact) - p.sigma;
    step = push > 0.0L ? 2.0L * rebound / push / 16.0L : s / 16.0L;
    t = t_impact + step;
    limit = chatter.next_release + s;
  }
  return chatter;
}

}  // namespace impactlab::testing
