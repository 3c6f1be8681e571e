// The rigid-body pendulum's events (rigid_pendulum_walls.hpp): impacts by the
// Newton–Coulomb impulse on the collision matrix, the contact problem at rest,
// releases and slip changes. Out of line so that the units that only run the
// system do not compile the rigid-body solvers again.
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

namespace impactlab {

auto RigidPendulumWalls::on_event(Mode mode, std::size_t k, CrossingKind crossing, const State& x,
                                  double t, EventLog& log) const -> Transition<State, Mode> {
  if (mode == Mode::free) return on_wall_reached(k == 0 ? 1 : -1, crossing, x, t, log);
  const int wall = wall_of(mode);
  if (k == 0) return release(wall, x, t, log);
  if (is_stick(mode)) return stick_breaks(mode, wall, k, x, t, log);
  return slip_stops(mode, wall, x, t, log);
}

rigidbody::GeneralizedContact<2> RigidPendulumWalls::free_spin_contact(int wall, const State& x,
                                                                       double t) const {
  rigidbody::GeneralizedContact<2> c;
  c.mass << rod_inertia_, 0.0, 0.0, ball_inertia_;
  c.forces << -p_.d * x[1] - p_.m * p_.l * effective_gravity(t) * std::sin(x[0]), 0.0;
  c.jacobian << -wall * p_.l * std::cos(x[0]), 0.0, -p_.l * std::sin(x[0]), -wall * r_;
  c.velocity_offset << 0.0, pivot_velocity(t);
  c.acceleration_drift << wall * p_.l * std::sin(x[0]) * x[1] * x[1],
      pivot_acceleration(t) - p_.l * std::cos(x[0]) * x[1] * x[1];
  return c;
}

rigidbody::GeneralizedContact<1> RigidPendulumWalls::locked_spin_contact(int wall, const State& x,
                                                                         double t) const {
  rigidbody::GeneralizedContact<1> c;
  c.mass << theta_inertia_;
  c.forces << -p_.d * x[1] - p_.m * p_.l * effective_gravity(t) * std::sin(x[0]);
  c.jacobian << -wall * p_.l * std::cos(x[0]), -p_.l * std::sin(x[0]) - wall * r_;
  c.velocity_offset << 0.0, pivot_velocity(t);
  c.acceleration_drift << wall * p_.l * std::sin(x[0]) * x[1] * x[1],
      pivot_acceleration(t) - p_.l * std::cos(x[0]) * x[1] * x[1];
  return c;
}

auto RigidPendulumWalls::stop_painleve(Mode mode, int wall, const State& x, double t,
                                       double qdot_after, EventLog& log) const
    -> Transition<State, Mode> {
  EventRecord painleve{t, EventKind::painleve, wall, x[0], x[1], qdot_after};
  painleve.tangential_velocity = tangential_velocity(wall, x, t);
  log.record(painleve);
  return {x, mode, t, true};
}

auto RigidPendulumWalls::impact_at(int wall, const State& x, double t) const -> WallImpact {
  const rigidbody::ImpactCoefficients coefficients{p_.e_n, p_.mu, 0.0};
  if (spin_free_) {
    const auto result = rigidbody::generalized_impact<2>(free_spin_contact(wall, x, t),
                                                         Eigen::Vector2d(x[1], x[3]), coefficients);
    return {result.qdot_after(0), result.qdot_after(1), result.impulse};
  }
  const auto result = rigidbody::generalized_impact<1>(
      locked_spin_contact(wall, x, t), Eigen::Matrix<double, 1, 1>(x[1]), coefficients);
  return {result.qdot_after(0), result.qdot_after(0), result.impulse};
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
  State after{wall * theta0_, impact.theta_dot, x[2], impact.phi_dot, x[4]};
  EventRecord record{t, EventKind::impact, wall, x[0], x[1], impact.theta_dot};
  record.normal_impulse = impact.impulse.normal_impulse;
  record.tangential_velocity = gamma_t;
  record.tangential_velocity_after = tangential_velocity(wall, after, t);
  log.record(record);

  // chattering, with Model N's rule: normal acceleration towards the wall
  // at rest, −γ̈_N = −(m l² / M_θ) g_e sin θ0 cos θ0, and its two rates
  const double share = rod_inertia_ / theta_inertia_;
  const double approach = -effective_gravity(t) * sin0_ * cos0_ * share;
  const double approach_rate = -effective_gravity_rate(t) * sin0_ * cos0_ * share;
  const double approach_curvature = -effective_gravity_curvature(t) * sin0_ * cos0_ * share;
  // damping d / M_θ (1/s); the gap's stiffness m l g_e cos θ0 / M_θ (1/s²)
  const double damping = p_.d / theta_inertia_;
  const double gap_stiffness = p_.m * p_.l * effective_gravity(t) * cos0_ / theta_inertia_;
  const auto estimate =
      accept_accumulation({p_.l * cos0_ * std::fabs(impact.theta_dot), approach, approach_rate,
                           p_.e_n, approach_curvature, damping, gap_stiffness},
                          p_.accumulation);
  if (!estimate) return {after, Mode::free, t, false};
  return enter_contact(wall, after, t + estimate->remaining, estimate->error_bound, log);
}

auto RigidPendulumWalls::settle(Mode from, int wall, const State& resting, double t, EventKind kind,
                                EventLog& log, bool slip_stopped) const -> Transition<State, Mode> {
  const double slip = slip_stopped ? 0.0 : tangential_velocity(wall, resting, t);
  const rigidbody::ContactForces forces =
      spin_free_
          ? rigidbody::contact_forces<2>(free_spin_contact(wall, resting, t), p_.mu, slip, 0.0)
          : rigidbody::contact_forces<1>(locked_spin_contact(wall, resting, t), p_.mu, slip, 0.0);
  if (forces.regime == rigidbody::ContactRegime::painleve_no_solution ||
      forces.regime == rigidbody::ContactRegime::painleve_ambiguous)
    return stop_painleve(from, wall, resting, t, 0.0, log);
  if (forces.regime == rigidbody::ContactRegime::detached) {
    if (kind != EventKind::contact_start) {
      EventRecord end{t, EventKind::contact_end, wall, resting[0], 0.0, 0.0};
      end.normal_force = 0.0;
      end.tangential_velocity = slip;
      end.friction_work = resting[4];
      log.record(end);
    }
    return {resting, Mode::free, t, false};
  }
  EventRecord record{t, kind, wall, resting[0], 0.0, 0.0};
  record.normal_force = forces.normal;
  record.tangential_velocity = slip;
  record.friction_work = resting[4];
  log.record(record);
  const Mode next = forces.regime == rigidbody::ContactRegime::stick
                        ? stick_mode(wall)
                        : slide_mode(wall, forces.slip_sign);
  return {resting, next, t, false};
}

auto RigidPendulumWalls::enter_contact(int wall, const State& after, double t, double time_error,
                                       EventLog& log) const -> Transition<State, Mode> {
  const State resting = on_wall(wall, after);
  EventRecord accumulation{t, EventKind::accumulation, wall, resting[0], 0.0, 0.0};
  accumulation.accumulation_error = time_error;
  log.record(accumulation);
  return settle(Mode::free, wall, resting, t, EventKind::contact_start, log);
}

auto RigidPendulumWalls::release(int wall, const State& x, double t, EventLog& log) const
    -> Transition<State, Mode> {
  EventRecord end{t, EventKind::contact_end, wall, wall * theta0_, 0.0, 0.0};
  end.normal_force = 0.0;
  end.tangential_velocity = tangential_velocity(wall, on_wall(wall, x), t);
  end.friction_work = x[4];
  log.record(end);
  return {on_wall(wall, x), Mode::free, t, false};
}

auto RigidPendulumWalls::slip_stops(Mode mode, int wall, const State& x, double t,
                                    EventLog& log) const -> Transition<State, Mode> {
  State resting = on_wall(wall, x);
  if (spin_free_) resting[3] = wall * pivot_velocity(t) / r_;  // γ_T = 0 exactly
  return settle(mode, wall, resting, t, EventKind::slip_reversal, log, true);
}

auto RigidPendulumWalls::stick_breaks(Mode mode, int wall, std::size_t k, const State& x, double t,
                                      EventLog& log) const -> Transition<State, Mode> {
  // the slip starts from zero: the integrated spin's round-off must not
  // start it on the wrong side of its witness
  State resting = on_wall(wall, x);
  resting[3] = wall * pivot_velocity(t) / r_;
  const double s = k == 1 ? -1.0 : 1.0;
  if (!(friction_denominator(s) > 1e-9)) return stop_painleve(mode, wall, resting, t, 0.0, log);
  EventRecord record{t, EventKind::slip_reversal, wall, resting[0], 0.0, 0.0};
  record.normal_force = sliding_normal_force(t, s);
  record.tangential_velocity = 0.0;
  record.friction_work = resting[4];
  log.record(record);
  return {resting, slide_mode(wall, s), t, false};
}

}  // namespace impactlab
