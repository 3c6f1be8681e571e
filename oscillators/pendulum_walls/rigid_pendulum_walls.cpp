// The rigid-body pendulum's events (rigid_pendulum_walls.hpp): which event
// happened, the contact in generalized coordinates, releases and Painlevé
// stops. The impact and the contact problem are in rigid_pendulum_impacts.cpp
// and rigid_pendulum_contacts.cpp: out of line, so that the units that only
// run the system do not compile the rigid-body solvers again, and apart, so
// that no unit compiles all of them.
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

auto RigidPendulumWalls::release(int wall, const State& x, double t, EventLog& log) const
    -> Transition<State, Mode> {
  EventRecord end{t, EventKind::contact_end, wall, wall * theta0_, 0.0, 0.0};
  end.normal_force = 0.0;
  end.tangential_velocity = tangential_velocity(wall, on_wall(wall, x), t);
  end.friction_work = x[friction_work];
  log.record(end);
  return {on_wall(wall, x), Mode::free, t, false};
}

}  // namespace impactlab
