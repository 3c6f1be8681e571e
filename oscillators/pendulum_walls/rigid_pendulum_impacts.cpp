// The rigid-body pendulum's impacts (rigid_pendulum_walls.hpp): the
// Newton–Coulomb impulse on the collision matrix at a wall, and the
// accumulation of impacts that ends in a contact.
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

#include <cmath>

namespace impactlab {

auto RigidPendulumWalls::impact_at(int wall, const State& x, double t) const -> WallImpact {
  const double friction_bound = wall == stick_forced_wall_ ? INFINITY : p_.mu;
  const rigidbody::ImpactCoefficients coefficients{p_.e_n, friction_bound, p_.e_t};
  if (spin_free_) {
    const auto result = rigidbody::generalized_impact<2>(free_spin_contact(wall, x, t),
                                                         Eigen::Vector2d(x[1], x[spin_rate]), coefficients);
    return {result.qdot_after(0), result.qdot_after(1), result.impulse};
  }
  const auto result = rigidbody::generalized_impact<1>(
      locked_spin_contact(wall, x, t), Eigen::Matrix<double, 1, 1>(x[1]), coefficients);
  return {result.qdot_after(0), result.qdot_after(0), result.impulse};
}

auto RigidPendulumWalls::impact_case(int wall, const State& x, double t) const -> ImpactCase {
  const rigidbody::NewtonCoulombImpulse<2> impulse = impact_at(wall, x, t).impulse;
  // the friction the stick needs: a stick impulse is the one the law took, a
  // slide's must be solved for
  const double needed = spin_free_ && impulse.regime == rigidbody::ImpulseRegime::stick
                            ? std::fabs(impulse.impulse(1)) / impulse.impulse(0)
                            : friction_to_stick(wall, x, t);
  // a forced stick takes the stick case's derivative whatever it needs
  const bool on_edge =
      wall != stick_forced_wall_ && std::fabs(needed - p_.mu) <= cone_edge_tolerance * p_.mu;
  // the slide's impulse is j (1, −μ s) with j > 0: s is the tangential part's opposite sign
  return {impulse.regime, impulse.impulse(1) > 0.0 ? -1.0 : 1.0, on_edge};
}

double RigidPendulumWalls::friction_to_stick(int wall, const State& x, double t) const {
  if (!spin_free_) return NAN;
  // the stick impulse is the one the law takes when no friction bound holds it
  const rigidbody::ImpactCoefficients unbounded{p_.e_n, INFINITY, p_.e_t};
  const auto result = rigidbody::generalized_impact<2>(
      free_spin_contact(wall, x, t), Eigen::Vector2d(x[1], x[spin_rate]), unbounded);
  if (result.impulse.regime != rigidbody::ImpulseRegime::stick) return NAN;
  return std::fabs(result.impulse.impulse(1)) / result.impulse.impulse(0);
}

auto RigidPendulumWalls::on_wall_reached(int wall, CrossingKind crossing, const State& x, double t,
                                         EventLog& log) const -> Transition<State, Mode> {
  const double gamma_t = tangential_velocity(wall, x, t);
  if (crossing == CrossingKind::grazing) {
    EventRecord graze{t, EventKind::grazing, wall, x[0], x[1], x[1]};
    graze.tangential_velocity = gamma_t;
    log.record(graze);
    return {x, Mode::free, t, false};
  }
  const WallImpact impact = impact_at(wall, x, t);
  if (impact.impulse.regime == rigidbody::ImpulseRegime::inconsistent)
    return stop_painleve(Mode::free, wall, x, t, x[1], log);
  State after{wall * theta0_, impact.theta_dot, impact.phi_dot, x[spin_angle], x[friction_work]};
  EventRecord record{t, EventKind::impact, wall, x[0], x[1], impact.theta_dot};
  record.normal_impulse = impact.impulse.normal_impulse;
  record.tangential_velocity = gamma_t;
  record.tangential_velocity_after = tangential_velocity(wall, after, t);
  record.sticks = impact.impulse.regime == rigidbody::ImpulseRegime::stick;
  log.record(record);

  // chattering, with Model N's rule: normal acceleration towards the wall
  // at rest, −γ̈_N = −(m l² / M_θ) g_e sin θ0 cos θ0, and its two rates
  const double share = rod_inertia_ / theta_inertia_;
  const double approach = approach_acceleration(t);
  const double approach_rate = approach_acceleration_rate(t);
  const double approach_curvature = -effective_gravity_curvature(t) * sin0_ * cos0_ * share;
  // damping d / M_θ (1/s); the gap's stiffness m l g_e cos θ0 / M_θ (1/s²)
  const double damping = normal_damping();
  const double gap_stiffness = p_.m * p_.l * effective_gravity(t) * cos0_ / theta_inertia_;
  const auto estimate =
      accept_accumulation({normal_speed(impact.theta_dot), approach, approach_rate,
                           p_.e_n, approach_curvature, damping, gap_stiffness},
                          p_.accumulation);
  if (!estimate) return {after, Mode::free, t, false};
  return enter_contact(wall, after, t + estimate->remaining, estimate->error_bound, log);
}

}  // namespace impactlab
