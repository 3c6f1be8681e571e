// The pendulum between two walls as a rigid-body scene (model = "rigid",
// docs/rigidbody.md): the rod of Model N with, at its end, a ball of radius r and
// mass m (a solid sphere, I_b = (2/5) m r² about its centre) that may spin on
// a frictionless bearing. Impacts are resolved by the general Newton–Coulomb
// impulse on the collision matrix K = W M⁻¹ Wᵀ (src/rigidbody/), persistent
// contacts by the acceleration-level contact problem (contact_phase.hpp).
//
// Generalized coordinates q = (θ, φ): θ the rod's angle from the downward
// vertical (rad, positive towards the right wall), φ the ball's absolute
// rotation angle in the same sense (rad). Pivot velocity V0 sin ωt, y down.
//     spin free    M = diag(m l², I_b),  h = (−d θ̇ − m l g_e sin θ, 0)
//     spin locked  φ ≡ θ: one coordinate, M = m l² + I_b
// The ball touches the wall x = ±b at the point of its surface nearest the
// wall, so the walls are reached at θ = ±θ0, sin θ0 = (b − r) / l. At wall
// w = ±1:
//     γ_N = −w l cos θ θ̇                    W_N = (−w l cos θ, 0)
//     γ_T = V0 sin ωt − l sin θ θ̇ − w r φ̇    W_T = (−l sin θ, −w r)
// (γ_T: velocity of the ball's material contact point along the wall, y down).
// With the spin locked W_T = −l sin θ − w r, and at r = 0 everything reduces
// to Model N (pendulum_walls.hpp): the same witnesses, the same accumulation
// rule, and the Newton–Coulomb impulse on the rank-one K slides with
// θ̇⁺ = −e_n θ̇⁻, which is Model N's impact law.
//
// Modes: free flight; sliding contact on a wall with a given slip direction
// (θ ≡ ±θ0, θ̇ = 0; the ball slides and, if free, is spun by friction); sticking contact (spin free
// only: the ball rolls on the wall as the pivot moves it). The stick case of
// the impulse sets the contact point's slip to γ_T⁺ = −e_t γ_T⁻, with the
// scene's e_t ∈ [−1, 0], the paper's e_y and its sign convention (0: the
// slip stops; −1: it is kept); a sliding impact's slip change emerges from
// the impulse mechanics.
// State: {θ, θ̇, φ̇, φ, W_f}, W_f the friction work in contact phases (J):
// the mechanical state first, so that (θ, θ̇) with the spin locked and
// (θ, θ̇, φ̇) with it free are the tangent space of the analyses
// (rigid_pendulum_spin.hpp). With the spin locked φ̇ turns with θ̇ and is
// bookkeeping: the contact velocities read θ̇.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include <impactlab/contact/accumulation.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/fast_trig.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include <impactlab/rigidbody/contact_phase.hpp>
#include <impactlab/rigidbody/generalized_system.hpp>

namespace impactlab {

struct RigidPendulumParameters {
  PendulumWallsParameters pendulum;  // m, l, b, d, g, V0, ω, e_n, μ, e_t
  double radius = 0.0;               // ball radius r (m), 0 <= r < b
  bool spin_free = false;            // ball on a free bearing (true) or fixed to the rod
};

class RigidPendulumWalls {
 public:
  using State = std::array<double, 5>;
  [[nodiscard]] std::vector<std::string_view> state_names() const {
    return {"theta", "theta_dot", "spin_rate", "spin_angle", "friction_work"};
  }
  // the state's components after θ (0) and θ̇ (1)
  static constexpr std::size_t spin_rate = 2;      // φ̇ (rad/s)
  static constexpr std::size_t spin_angle = 3;     // φ (rad)
  static constexpr std::size_t friction_work = 4;  // W_f (J)
  // slide modes carry the slip's sign s = sgn γ_T (pos: the contact point
  // slides down the wall, y down), so that the friction's direction is that
  // of the mode and not of a slip that sits at zero to round-off
  enum class Mode {
    free,
    slide_right_pos,
    slide_right_neg,
    slide_left_pos,
    slide_left_neg,
    stick_right,
    stick_left,
  };
  static constexpr std::size_t max_witnesses = 3;

  explicit RigidPendulumWalls(const RigidPendulumParameters& p)
      : p_(p.pendulum),
        r_(p.radius),
        spin_free_(p.spin_free),
        ball_inertia_(0.4 * p.pendulum.m * p.radius * p.radius),
        rod_inertia_(p.pendulum.m * p.pendulum.l * p.pendulum.l),
        theta_inertia_(spin_free_ ? rod_inertia_ : rod_inertia_ + ball_inertia_),
        sin0_((p.pendulum.b - p.radius) / p.pendulum.l),
        theta0_(std::asin(sin0_)),
        cos0_(std::cos(theta0_)) {}

  // the wall (+1 / −1) of a contact mode, and whether the ball sticks (rolls) in it
  static int wall_of(Mode mode) {
    return mode == Mode::slide_right_pos || mode == Mode::slide_right_neg ||
                   mode == Mode::stick_right
               ? 1
               : -1;
  }
  static bool is_stick(Mode mode) { return mode == Mode::stick_right || mode == Mode::stick_left; }

  [[nodiscard]] double wall_angle() const { return theta0_; }
  [[nodiscard]] double ball_inertia() const { return ball_inertia_; }
  [[nodiscard]] double radius() const { return r_; }
  [[nodiscard]] bool spin_free() const { return spin_free_; }
  // the pendulum's own parameters (m, l, b, d, g, V0, ω, e_n, μ, e_t)
  [[nodiscard]] const PendulumWallsParameters& parameters() const { return p_; }

  // Every impact at the wall of flight witness k (0: the right wall, +1; 1:
  // the left, −1) sticks, whatever friction it needs: the impulse law with
  // no bound on friction there. Not a model of anything: the map whose
  // fixed points are the orbits with an impulse on the friction cone's edge
  // (docs/rigidbody.md, "Orbits that stick on the cone's edge"), smooth
  // where the real map has no tangent map, so that continuation can follow
  // them (analysis/continuation_problem.hpp, stick_forced_at).
  void force_stick_at_witness(std::size_t k) { stick_forced_wall_ = k == 0 ? 1 : -1; }

  // effective gravity in the pivot's frame (m/s²), its rate (m/s³), the
  // pivot's velocity (m/s) and acceleration (m/s²) along the wall; like the
  // right-hand side and the witnesses, written over a number type (a series
  // type runs through them: integrate/taylor_series.hpp)
  template <class Number>
  [[nodiscard]] Number effective_gravity(const Number& t) const {
    return p_.g - p_.V0 * p_.omega * cos_phase(p_.omega * t);
  }
  template <class Number>
  [[nodiscard]] Number effective_gravity_rate(const Number& t) const {
    using std::sin;
    return p_.V0 * p_.omega * p_.omega * sin(p_.omega * t);
  }
  [[nodiscard]] double effective_gravity_curvature(double t) const {
    return p_.V0 * p_.omega * p_.omega * p_.omega * std::cos(p_.omega * t);
  }
  template <class Number>
  [[nodiscard]] Number pivot_velocity(const Number& t) const {
    using std::sin;
    return p_.V0 * sin(p_.omega * t);
  }
  template <class Number>
  [[nodiscard]] Number pivot_acceleration(const Number& t) const {
    return p_.V0 * p_.omega * cos_phase(p_.omega * t);
  }

  // the normal acceleration towards a wall of the ball resting on it,
  // −γ̈_N = −(m l² / M_θ) g_e sin θ0 cos θ0 (m/s²): what drives a chatter
  // into its accumulation point (contact/accumulation.hpp), as in Model N
  template <class Number>
  [[nodiscard]] Number approach_acceleration(const Number& t) const {
    return -effective_gravity(t) * sin0_ * cos0_ * (rod_inertia_ / theta_inertia_);
  }
  // its rate (m/s³)
  template <class Number>
  [[nodiscard]] Number approach_acceleration_rate(const Number& t) const {
    return -effective_gravity_rate(t) * sin0_ * cos0_ * (rod_inertia_ / theta_inertia_);
  }
  // the damping of the normal motion near a wall, d / M_θ (1/s)
  [[nodiscard]] double normal_damping() const { return p_.d / theta_inertia_; }
  // the normal speed of an impact, l cos θ0 |θ̇| (m/s)
  template <class Number>
  [[nodiscard]] Number normal_speed(const Number& theta_rate) const {
    using std::fabs;
    return p_.l * cos0_ * fabs(theta_rate);
  }

  // γ_T at wall w (m/s)
  template <class Number>
  [[nodiscard]] Number tangential_velocity(int wall, const std::array<Number, 5>& x,
                                           const Number& t) const {
    using std::sin;
    return pivot_velocity(t) - p_.l * sin(x[0]) * x[1] - wall * r_ * x[spin_free_ ? spin_rate : 1];
  }

  [[nodiscard]] double max_step() const {
    const double forcing_period = 2.0 * std::numbers::pi / p_.omega;
    const double natural_period = 2.0 * std::numbers::pi * std::sqrt(p_.l / p_.g);
    // the damping's relaxation time m l²/d (s): an explicit stepper cannot step
    // much past it, so that an overdamped scene (m = 1e-12 kg, d = 1e12) is
    // sized by it up front (api/run_system.hpp) instead of crawling
    const double damping_period = 2.0 * std::numbers::pi * p_.m * p_.l * p_.l / p_.d;
    return std::min({forcing_period, natural_period, damping_period}) / 16.0;
  }

  // Written once over a number type: double for the Runge–Kutta steppers, a
  // Taylor series type for the Taylor stepper (the unqualified calls find its
  // own sin, fabs and core/fast_trig.hpp's names).
  template <class Number>
  void rhs(Mode mode, const std::array<Number, 5>& x, std::array<Number, 5>& dxdt,
           const Number& t) const {
    if (mode == Mode::free) {
      dxdt[0] = x[1];
      dxdt[1] = -(p_.d * x[1] + p_.m * p_.l * effective_gravity(t) * sin_angle(x[0])) /
                theta_inertia_;
      dxdt[spin_angle] = x[spin_rate];
      if (spin_free_)
        dxdt[spin_rate] = 0.0;
      else
        dxdt[spin_rate] = dxdt[1];
      dxdt[friction_work] = 0.0;
      return;
    }
    const int wall = wall_of(mode);
    dxdt[0] = 0.0;
    dxdt[1] = 0.0;
    dxdt[spin_angle] = x[spin_rate];
    if (is_stick(mode)) {
      // rolling on the wall: γ̇_T = V0 ω cos ωt − w r φ̈ = 0
      dxdt[spin_rate] = wall * pivot_acceleration(t) / r_;
      dxdt[friction_work] = 0.0;
      return;
    }
    using std::fabs;
    const Number slip = tangential_velocity(wall, x, t);
    const double s = slip_sign_of(mode);
    const Number lambda_n = sliding_normal_force(t, s);
    // I_b φ̈ = W_T,φ λ_T = (−w r)(−μ s λ_N)
    if (spin_free_)
      dxdt[spin_rate] = wall * r_ * p_.mu * s * lambda_n / ball_inertia_;
    else
      dxdt[spin_rate] = 0.0;
    dxdt[friction_work] = p_.mu * lambda_n * fabs(slip);
  }

  // free and slide: 2; stick: 3 (the cone's two edges)
  [[nodiscard]] std::size_t witness_count(Mode mode) const { return is_stick(mode) ? 3 : 2; }

  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    if (mode == Mode::free || k == 0 || is_stick(mode)) return TriggerDirection::falling;
    return slip_sign_of(mode) > 0.0 ? TriggerDirection::falling : TriggerDirection::rising;
  }

  // free:  k = 0, 1 angular gaps θ0 ∓ θ to the right and left walls (rad)
  // slide: k = 0 the frictionless normal force −m g_e tan θ0 (N), with the
  //        sign and zeros of λ_N while the contact is consistent (as Model N);
  //        k = 1 the slip γ_T (m/s), reaching zero from the mode's side
  // stick: k = 0 the sticking normal force λ_N (N); k = 1, 2 the friction
  //        cone's margins μ λ_N − λ_T and μ λ_N + λ_T (N): two smooth
  //        witnesses instead of μ λ_N − |λ_T|, whose kink where λ_T changes
  //        sign a polynomial dense output would carry on past
  template <class Number>
  [[nodiscard]] BasicWitnessSample<Number> witness(Mode mode, std::size_t k,
                                                   const std::array<Number, 5>& x,
                                                   const Number& t) const {
    if (mode == Mode::free) {
      const double side = k == 0 ? 1.0 : -1.0;
      return {theta0_ - side * x[0], -side * x[1]};
    }
    const int wall = wall_of(mode);
    if (is_stick(mode)) {
      const StickForces<Number> f = stick_forces(t);
      if (k == 0) return {f.normal, f.normal_rate};
      const double edge = k == 1 ? 1.0 : -1.0;
      return {p_.mu * f.normal - edge * f.tangential,
              p_.mu * f.normal_rate - edge * f.tangential_rate};
    }
    if (k == 0)
      return {-p_.m * effective_gravity(t) * sin0_ / cos0_,
              -p_.m * effective_gravity_rate(t) * sin0_ / cos0_};
    const Number slip = tangential_velocity(wall, x, t);
    const double s = slip_sign_of(mode);
    if (!spin_free_) return {slip, pivot_acceleration(t)};
    const Number spin_acceleration =
        wall * r_ * p_.mu * s * sliding_normal_force(t, s) / ball_inertia_;
    return {slip, pivot_acceleration(t) - wall * r_ * spin_acceleration};
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing,
                                   const State& x, double t, EventLog& log) const;

  // Whether a state on a wall (|θ| = θ0) at time t has no motion to go on
  // with: moving into the wall, an impulse with no admissible solution; at
  // rest, a contact problem with none or several (Painlevé). False off the walls.
  [[nodiscard]] bool painleve_on_wall(const State& x, double t) const;

  // Which case of the Newton–Coulomb impulse an impact at wall w takes from
  // state x at time t: stick, slide (with the slip's sign s, which fixes the
  // friction's direction), or neither (separating, inconsistent); and whether
  // its impulse lies on the friction cone's edge, |μ − friction_to_stick| ≤
  // cone_edge_tolerance μ (spin free only: with the spin locked the stick
  // case is reached only where the slip is zero), where the two cases give
  // the same rates but not the same derivatives.
  static constexpr double cone_edge_tolerance = 1e-8;
  struct ImpactCase {
    rigidbody::ImpulseRegime regime = rigidbody::ImpulseRegime::separating;
    double slip_sign = 1.0;
    bool on_cone_edge = false;
  };
  [[nodiscard]] ImpactCase impact_case(int wall, const State& x, double t) const;
  // The friction coefficient an impact at wall w from (x, t) needs to stick,
  // |J_T| / J_N of the stick impulse (spin free): the impact sticks for
  // μ ≥ this and slides below it. NaN where no stick impulse pushes the ball
  // off the wall (J_N < 0) or the spin is locked.
  [[nodiscard]] double friction_to_stick(int wall, const State& x, double t) const;

  // The rates (θ̇⁺, φ̇⁺) just after an impact at wall w in a given case of
  // the impulse, over a number type: the impulse law of
  // src/rigidbody/newton_coulomb_impulse.hpp written out for
  // this contact, where M is diagonal, K = W M⁻¹ Wᵀ has the entries below
  // and n = (1, 0). Within one case the rates are smooth in (x, t), so a
  // dual number run through this gives the reset's Jacobian
  // (rigid_pendulum_spin.hpp); on doubles it is impact_at's result to
  // round-off (tests/oscillators/rigid_pendulum_spin_test.cpp).
  //   slide  J = j (1, −μ s),  j = −(1 + e_n) γ_N / (K_NN − μ s K_NT)
  //   stick  K J = (−(1 + e_n) γ_N, −(1 + e_t) γ_T): J = K⁻¹ Δγ with the spin free;
  //          with it locked K has rank one and only γ_N⁺ = −e_n γ_N⁻ binds
  //   then   q̇⁺ = q̇⁻ + M⁻¹ Wᵀ J
  template <class Number>
  [[nodiscard]] std::array<Number, 2> rates_after_impact(int wall, const ImpactCase& impact,
                                                         const std::array<Number, 5>& x,
                                                         const Number& t) const {
    using std::cos;
    using std::sin;
    const Number c = cos(x[0]), s = sin(x[0]);
    // W_N = (−w l cos θ, 0); W_T = (−l sin θ, −w r) free, −l sin θ − w r locked
    const Number w_n = -wall * p_.l * c;
    const Number w_t = -p_.l * s - (spin_free_ ? 0.0 : wall * r_);
    const Number gamma_n = w_n * x[1];
    const Number gamma_t = tangential_velocity(wall, x, t);
    const double inverse_theta_mass = 1.0 / theta_inertia_;
    const double inverse_spin_mass = spin_free_ ? 1.0 / ball_inertia_ : 0.0;
    const double spin_arm = spin_free_ ? -wall * r_ : 0.0;  // W_T,φ
    const Number k_nn = w_n * w_n * inverse_theta_mass;
    const Number k_nt = w_n * w_t * inverse_theta_mass;
    const Number k_tt = w_t * w_t * inverse_theta_mass + spin_arm * spin_arm * inverse_spin_mass;
    Number impulse_n, impulse_t;
    if (impact.regime == rigidbody::ImpulseRegime::stick && spin_free_) {
      const Number delta_n = -(1.0 + p_.e_n) * gamma_n;
      const Number delta_t = -(1.0 + p_.e_t) * gamma_t;
      const Number determinant = k_nn * k_tt - k_nt * k_nt;
      impulse_n = (k_tt * delta_n - k_nt * delta_t) / determinant;
      impulse_t = (k_nn * delta_t - k_nt * delta_n) / determinant;
    } else if (impact.regime == rigidbody::ImpulseRegime::stick) {
      const Number theta_rate = x[1] - (1.0 + p_.e_n) * gamma_n / w_n;
      return {theta_rate, theta_rate};
    } else {
      const double friction = p_.mu * impact.slip_sign;
      impulse_n = -(1.0 + p_.e_n) * gamma_n / (k_nn - friction * k_nt);
      impulse_t = -friction * impulse_n;
    }
    const Number theta_rate = x[1] + (w_n * impulse_n + w_t * impulse_t) * inverse_theta_mass;
    if (!spin_free_) return {theta_rate, theta_rate};
    return {theta_rate, x[spin_rate] + spin_arm * impulse_t * inverse_spin_mass};
  }

  // The contact of wall w in generalized coordinates at state x, time t
  // (generalized_system.hpp), for the spin free (N = 2) or locked (N = 1).
  [[nodiscard]] rigidbody::GeneralizedContact<2> free_spin_contact(int wall, const State& x,
                                                                   double t) const;
  [[nodiscard]] rigidbody::GeneralizedContact<1> locked_spin_contact(int wall, const State& x,
                                                                     double t) const;

 private:
  template <class Number>
  struct StickForces {
    Number normal, normal_rate;          // λ_N (N), λ̇_N (N/s)
    Number tangential, tangential_rate;  // λ_T (N), λ̇_T (N/s)
  };

  static double slip_sign_of(Mode mode) {
    return mode == Mode::slide_right_pos || mode == Mode::slide_left_pos ? 1.0 : -1.0;
  }
  static Mode slide_mode(int wall, double s) {
    if (wall > 0) return s > 0.0 ? Mode::slide_right_pos : Mode::slide_right_neg;
    return s > 0.0 ? Mode::slide_left_pos : Mode::slide_left_neg;
  }
  static Mode stick_mode(int wall) { return wall > 0 ? Mode::stick_right : Mode::stick_left; }

  // λ_N of a sliding contact at rest on either wall with slip sign s (θ̈ = 0):
  // λ_N = −h_θ / (W_N − μ s W_T,θ), W_T,θ = −w (l sin θ0 + r) with the spin
  // locked (the ball turns with the rod), −w l sin θ0 with it free:
  // λ_N = −m g_e sin θ0 / (cos θ0 − s μ (sin θ0 + r_locked / l))
  template <class Number>
  [[nodiscard]] Number sliding_normal_force(const Number& t, double s) const {
    return -p_.m * effective_gravity(t) * sin0_ / friction_denominator(s);
  }
  [[nodiscard]] double friction_denominator(double s) const {
    const double locked_radius = spin_free_ ? 0.0 : r_;
    return cos0_ - s * p_.mu * (sin0_ + locked_radius / p_.l);
  }
  // no consistent slide with slip sign s (the denominator at or below zero)
  [[nodiscard]] bool painleve_sliding(double s) const { return !(friction_denominator(s) > 1e-9); }
  // the slip that starts where the friction force leaves the cone's edge
  // `edge` (stick witness 1: λ_T = μ λ_N, 2: λ_T = −μ λ_N), opposite to λ_T
  static double slip_sign_leaving(std::size_t edge) { return edge == 1 ? -1.0 : 1.0; }

  // sticking on wall w, the same on both (spin free, θ̈ = 0, γ̇_T = 0): I_b φ̈ = −w r λ_T with
  // φ̈ = w V0 ω cos ωt / r gives λ_T = −I_b V0 ω cos ωt / r²; then
  // 0 = h_θ + W_N λ_N + W_T,θ λ_T gives λ_N = −m g_e tan θ0 − tan θ0 λ_T
  template <class Number>
  [[nodiscard]] StickForces<Number> stick_forces(const Number& t) const {
    using std::sin;
    const double tan0 = sin0_ / cos0_;
    const Number lambda_t = -ball_inertia_ * pivot_acceleration(t) / (r_ * r_);
    const Number lambda_t_rate =
        ball_inertia_ * p_.V0 * p_.omega * p_.omega * sin(p_.omega * t) / (r_ * r_);
    return {-p_.m * effective_gravity(t) * tan0 - tan0 * lambda_t,
            -p_.m * effective_gravity_rate(t) * tan0 - tan0 * lambda_t_rate, lambda_t,
            lambda_t_rate};
  }

  [[nodiscard]] State on_wall(int wall, const State& x) const {
    return {wall * theta0_, 0.0, spin_free_ ? x[spin_rate] : 0.0, x[spin_angle], x[friction_work]};
  }

  Transition<State, Mode> stop_painleve(Mode mode, int wall, const State& x, double t,
                                        double qdot_after, EventLog& log) const;

  // the Newton–Coulomb impulse at wall w: θ̇⁺, φ̇⁺ and the impulse
  struct WallImpact {
    double theta_dot, phi_dot;
    rigidbody::NewtonCoulombImpulse<2> impulse;
  };
  [[nodiscard]] WallImpact impact_at(int wall, const State& x, double t) const;

  Transition<State, Mode> on_wall_reached(int wall, CrossingKind crossing, const State& x,
                                          double t, EventLog& log) const;

  // The contact problem at rest on wall w at time t: which contact mode, or
  // a Painlevé stop, or free flight (no compressive force).
  // slip_stopped: the event is the slip reaching zero, so γ_T = 0 whatever
  // its round-off (the contact problem then decides stick or slide, and the
  // slide's direction).
  Transition<State, Mode> settle(Mode from, int wall, const State& resting, double t,
                                 EventKind kind, EventLog& log, bool slip_stopped = false) const;

  // the contact problem at rest on wall w with tangential velocity `slip` (m/s)
  [[nodiscard]] rigidbody::ContactForces contact_forces_at(int wall, const State& resting, double t,
                                                           double slip) const;

  Transition<State, Mode> enter_contact(int wall, const State& after, double t,
                                        double time_error, EventLog& log) const;

  Transition<State, Mode> release(int wall, const State& x, double t, EventLog& log) const;

  // the slip reached zero: stick, or slide on in the direction the contact
  // problem allows (a slip reversal)
  Transition<State, Mode> slip_stops(Mode mode, int wall, const State& x, double t,
                                     EventLog& log) const;

  // the friction force reached the cone's edge (witness k = 1: λ_T = μ λ_N,
  // k = 2: λ_T = −μ λ_N): slip starts opposite to λ_T
  Transition<State, Mode> stick_breaks(Mode mode, int wall, std::size_t k, const State& x,
                                       double t, EventLog& log) const;

  PendulumWallsParameters p_;
  double r_;              // ball radius (m)
  bool spin_free_;
  double ball_inertia_;   // I_b (kg m²)
  double rod_inertia_;    // m l² (kg m²)
  double theta_inertia_;  // M_θ: m l² (spin free) or m l² + I_b (locked) (kg m²)
  double sin0_, theta0_, cos0_;
  int stick_forced_wall_ = 0;  // the wall whose impacts always stick (0: none)
};

static_assert(HybridSystem<RigidPendulumWalls>);
static_assert(HasSeriesRhs<RigidPendulumWalls>);

}  // namespace impactlab
