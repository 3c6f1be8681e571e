// The rigid-body pendulum's contact problem at rest on a wall
// (rigid_pendulum_walls.hpp): whether it sticks, slides or releases, and the
// slip's changes.
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

namespace impactlab {

auto RigidPendulumWalls::settle(Mode from, int wall, const State& resting, double t, EventKind kind,
                                EventLog& log, bool slip_stopped) const -> Transition<State, Mode> {
  const double slip = slip_stopped ? 0.0 : tangential_velocity(wall, resting, t);
  const rigidbody::ContactForces forces = contact_forces_at(wall, resting, t, slip);
  if (forces.regime == rigidbody::ContactRegime::painleve_no_solution ||
      forces.regime == rigidbody::ContactRegime::painleve_ambiguous)
    return stop_painleve(from, wall, resting, t, 0.0, log);
  if (forces.regime == rigidbody::ContactRegime::detached) {
    if (kind != EventKind::contact_start) {
      EventRecord end{t, EventKind::contact_end, wall, resting[0], 0.0, 0.0};
      end.normal_force = 0.0;
      end.tangential_velocity = slip;
      end.friction_work = resting[friction_work];
      log.record(end);
    }
    return {resting, Mode::free, t, false};
  }
  Mode next = forces.regime == rigidbody::ContactRegime::stick
                  ? stick_mode(wall)
                  : slide_mode(wall, forces.slip_sign);
  double normal = forces.normal;
  // A stick on the friction cone's edge whose margin is falling ends at
  // once: the slip starts there, as stick_breaks would start it. Sticking
  // instead (the contact problem allows it, on the edge) handed the next
  // instant to stick_breaks, its slide at once to slip_stops, and back: a
  // run that stopped with no_progress (μ = 9 at V0 = 5, r = 0.01). The slide
  // continues from γ_T = 0, where its slip witness is not armed again until
  // the slip has left zero.
  if (forces.regime == rigidbody::ContactRegime::stick) {
    for (std::size_t edge = 1; edge <= 2; ++edge) {
      const WitnessSample margin = witness(stick_mode(wall), edge, resting, t);
      if (!(margin.value <= 1e-9 * p_.mu * std::fabs(forces.normal) && margin.rate < 0.0)) continue;
      const double s = slip_sign_leaving(edge);
      if (painleve_sliding(s)) return stop_painleve(from, wall, resting, t, 0.0, log);
      next = slide_mode(wall, s);
      normal = sliding_normal_force(t, s);
      break;
    }
  }
  EventRecord record{t, kind, wall, resting[0], 0.0, 0.0};
  record.normal_force = normal;
  record.tangential_velocity = slip;
  record.friction_work = resting[friction_work];
  log.record(record);
  return {resting, next, t, false};
}

rigidbody::ContactForces RigidPendulumWalls::contact_forces_at(int wall, const State& resting,
                                                               double t, double slip) const {
  return spin_free_
             ? rigidbody::contact_forces<2>(free_spin_contact(wall, resting, t), p_.mu, slip, 0.0)
             : rigidbody::contact_forces<1>(locked_spin_contact(wall, resting, t), p_.mu, slip, 0.0);
}

bool RigidPendulumWalls::painleve_on_wall(const State& x, double t) const {
  if (!(std::fabs(x[0]) >= theta0_)) return false;
  const int wall = x[0] > 0.0 ? 1 : -1;
  if (wall * x[1] > 0.0) return impact_case(wall, x, t).regime == rigidbody::ImpulseRegime::inconsistent;
  const State resting = on_wall(wall, x);
  const rigidbody::ContactForces forces =
      contact_forces_at(wall, resting, t, tangential_velocity(wall, resting, t));
  return forces.regime == rigidbody::ContactRegime::painleve_no_solution ||
         forces.regime == rigidbody::ContactRegime::painleve_ambiguous;
}

auto RigidPendulumWalls::enter_contact(int wall, const State& after, double t, double time_error,
                                       EventLog& log) const -> Transition<State, Mode> {
  const State resting = on_wall(wall, after);
  EventRecord accumulation{t, EventKind::accumulation, wall, resting[0], 0.0, 0.0};
  accumulation.accumulation_error = time_error;
  log.record(accumulation);
  return settle(Mode::free, wall, resting, t, EventKind::contact_start, log);
}

auto RigidPendulumWalls::slip_stops(Mode mode, int wall, const State& x, double t,
                                    EventLog& log) const -> Transition<State, Mode> {
  State resting = on_wall(wall, x);
  if (spin_free_) resting[spin_rate] = wall * pivot_velocity(t) / r_;  // γ_T = 0 exactly
  return settle(mode, wall, resting, t, EventKind::slip_reversal, log, true);
}

auto RigidPendulumWalls::stick_breaks(Mode mode, int wall, std::size_t k, const State& x, double t,
                                      EventLog& log) const -> Transition<State, Mode> {
  // the slip starts from zero: the integrated spin's round-off must not
  // start it on the wrong side of its witness
  State resting = on_wall(wall, x);
  resting[spin_rate] = wall * pivot_velocity(t) / r_;
  const double s = slip_sign_leaving(k);
  if (painleve_sliding(s)) return stop_painleve(mode, wall, resting, t, 0.0, log);
  EventRecord record{t, EventKind::slip_reversal, wall, resting[0], 0.0, 0.0};
  record.normal_force = sliding_normal_force(t, s);
  record.tangential_velocity = 0.0;
  record.friction_work = resting[friction_work];
  log.record(record);
  return {resting, slide_mode(wall, s), t, false};
}

}  // namespace impactlab
