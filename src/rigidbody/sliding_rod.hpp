// The classic Painlevé rod as a hybrid system: a uniform rod (mass m, length
// 2a, I = m a²/3) whose lower end slides on a rough floor y = 0, moved by the
// event loop of simulate/simulator.hpp with its contact resolved at acceleration
// level (contact_phase.hpp).
//
// Coordinates q = (x, y, θ) of the centre and the angle to the floor; the
// lower end is (x − a cos θ, y − a sin θ):
//     γ_N = ẏ − a cos θ θ̇        W_N = (0, 1, −a cos θ)
//     γ_T = ẋ + a sin θ θ̇        W_T = (1, 0,  a sin θ)
// Sliding with s = sgn γ_T, the normal force needs
//     A = (1 + 3 cos²θ + 3 μ s sin θ cos θ) / m > 0,
// which fails for s = −1 once μ > (1 + 3cos²θ)/(3 sin θ cos θ) ≥ 4/3 (the
// minimum at tan θ = 2). A is a witness: where it reaches zero the contact
// problem has no solution (or two) and the run stops with a `painleve` event
// carrying the time and state, instead of integrating a force that diverges.
// Approached from a consistent slide with a_N < 0, λ_N = −a_N / A grows
// without bound and the friction stops the slip before A reaches zero (the
// classic "jam"); the end of the slip is then classified by the contact
// problem with γ_T = 0, and a Painlevé configuration is reported there. This
// is a diagnostic scene: lift-off and the end of the slip stop the run
// (contact_end, slip_reversal or painleve); nothing is resolved past them
// (a tangential impact would be needed: Génot & Brogliato, Eur. J. Mech.
// A/Solids 18 (1999) 653–677).
// State: {x, y, θ, ẋ, ẏ, θ̇} (m, m, rad, m/s, m/s, rad/s).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/rigidbody/contact_phase.hpp>
#include <impactlab/rigidbody/generalized_system.hpp>

namespace impactlab::rigidbody {

struct SlidingRodParameters {
  double m = 1.0;   // mass (kg)
  double a = 0.5;   // half-length (m)
  double g = 9.81;  // gravity (m/s²)
  double mu = 0.5;  // Coulomb friction
};

class SlidingRod {
 public:
  using State = std::array<double, 6>;
  enum class Mode { slide };
  static constexpr std::size_t max_witnesses = 3;

  explicit SlidingRod(const SlidingRodParameters& p) : p_(p), inertia_(p.m * p.a * p.a / 3.0) {}

  [[nodiscard]] GeneralizedContact<3> contact(const State& x) const {
    GeneralizedContact<3> c;
    c.mass = Eigen::Vector3d(p_.m, p_.m, inertia_).asDiagonal();
    c.forces << 0.0, -p_.m * p_.g, 0.0;
    const double s = std::sin(x[2]), co = std::cos(x[2]);
    c.jacobian << 0.0, 1.0, -p_.a * co, 1.0, 0.0, p_.a * s;
    c.acceleration_drift << p_.a * s * x[5] * x[5], p_.a * co * x[5] * x[5];
    return c;
  }
  [[nodiscard]] double slip(const State& x) const { return x[3] + p_.a * std::sin(x[2]) * x[5]; }
  [[nodiscard]] double slip_sign(const State& x) const { return slip(x) > 0.0 ? 1.0 : -1.0; }

  // m A = 1 + 3 cos²θ + 3 μ s sin θ cos θ (dimensionless)
  [[nodiscard]] double scaled_denominator(double theta, double s) const {
    const double co = std::cos(theta), si = std::sin(theta);
    return 1.0 + 3.0 * co * co + 3.0 * p_.mu * s * si * co;
  }

  [[nodiscard]] double max_step() const { return 0.01; }

  void rhs(Mode, const State& x, State& dxdt, double) const {
    const GeneralizedContact<3> c = contact(x);
    const ContactForces f = detail::sliding_forces(
        c.collision_matrix(),
        c.jacobian * Eigen::LLT<Eigen::Matrix3d>(c.mass).solve(c.forces) + c.acceleration_drift,
        p_.mu, slip_sign(x));
    const Eigen::Vector3d qdd = c.acceleration({f.normal, f.tangential});
    dxdt = {x[3], x[4], x[5], qdd(0), qdd(1), qdd(2)};
  }

  [[nodiscard]] std::size_t witness_count(Mode) const { return 3; }
  [[nodiscard]] TriggerDirection trigger_direction(Mode, std::size_t k) const {
    return k == 2 ? TriggerDirection::either : TriggerDirection::falling;
  }

  // k = 0: m A − margin, the Painlevé denominator; k = 1: the unclamped
  // normal force −a_N / A (N), release where it vanishes; k = 2: the slip (m/s).
  // Rates by the chain rule in θ (and θ̇ for a_N) along the flow.
  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& x, double t) const {
    const double s = slip_sign(x);
    if (k == 0) {
      const double co = std::cos(x[2]), si = std::sin(x[2]);
      const double d_theta = -6.0 * co * si + 3.0 * p_.mu * s * (co * co - si * si);
      return {scaled_denominator(x[2], s) - 1e-6, d_theta * x[5]};
    }
    State dxdt;
    rhs(mode, x, dxdt, t);
    if (k == 1) {
      const double co = std::cos(x[2]), si = std::sin(x[2]);
      const double a_n = -p_.g + p_.a * si * x[5] * x[5];
      const double a_n_rate = p_.a * (co * x[5] * x[5] * x[5] + 2.0 * si * x[5] * dxdt[5]);
      const double d = scaled_denominator(x[2], s);
      const double d_rate = (-6.0 * co * si + 3.0 * p_.mu * s * (co * co - si * si)) * x[5];
      return {-p_.m * a_n / d, -p_.m * (a_n_rate * d - a_n * d_rate) / (d * d)};
    }
    return {slip(x), dxdt[3] + p_.a * (std::cos(x[2]) * x[5] * x[5] + std::sin(x[2]) * dxdt[5])};
  }

  // Every event stops the run. At the end of the slip the contact problem
  // with γ_T = 0 is classified: a Painlevé configuration is reported as such.
  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind, const State& x,
                                   double t, EventLog& log) const {
    EventKind kind = k == 0 ? EventKind::painleve
                     : k == 1 ? EventKind::contact_end
                              : EventKind::slip_reversal;
    if (k == 2) {
      const ContactRegime regime = contact_forces<3>(contact(x), p_.mu, 0.0, 0.0).regime;
      if (regime == ContactRegime::painleve_no_solution ||
          regime == ContactRegime::painleve_ambiguous)
        kind = EventKind::painleve;
    }
    EventRecord record{t, kind, 0, x[2], x[5], x[5]};
    record.tangential_velocity = slip(x);
    log.record(record);
    return {x, mode, t, true};
  }

 private:
  SlidingRodParameters p_;
  double inertia_;  // m a² / 3 (kg m²)
};

static_assert(HybridSystem<SlidingRod>);

}  // namespace impactlab::rigidbody
