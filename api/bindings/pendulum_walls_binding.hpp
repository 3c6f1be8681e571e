// The pendulum between two walls (oscillators/pendulum_walls/): one scene
// schema, three models, each running every analysis: Model N (newton),
// Model P (paper; no Jacobians, so no Floquet, Lyapunov or continuation) and
// the rigid-body model (rigid), one binding per spin. api/scene_system.hpp
// says what a binding is.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/scene_boundary.hpp>
#include <impactlab/api/bindings/pendulum_walls_parameters.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/event_columns.hpp>
#include <impactlab/io/event_extension.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_spin.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>
#include <impactlab/oscillators/pendulum_walls/sliding_impact.hpp>

namespace impactlab {

const SceneSchema& pendulum_walls_schema();

std::string_view pendulum_mode_name(PendulumMode mode);
std::string_view rigid_pendulum_mode_name(RigidPendulumWalls::Mode mode);

// The bob on a wall at rest, or beyond a moved wall, starts on it at rest in
// free flight (the event at t0 decides contact again); the friction work and
// Model P's pending release rate restart from zero.
template <class State>
void admit_pendulum_state(double wall_angle, State& x, PendulumMode& mode) {
  if (mode != PendulumMode::free) {
    x[0] = mode == PendulumMode::contact_right ? wall_angle : -wall_angle;
    x[1] = 0.0;
  }
  if (std::fabs(x[0]) > wall_angle) x[0] = std::copysign(wall_angle, x[0]);
  for (std::size_t i = 2; i < x.size(); ++i) x[i] = 0.0;
  mode = PendulumMode::free;
}

// meta.json's derived quantities of Models N and P: the friction work, and
// for Model P the sliding impacts (contact phases that start at an impact,
// not at the accumulation point of a chatter) and the slip's end velocity.
class PendulumRunTally {
 public:
  PendulumRunTally(const PendulumWallsParameters& parameters, double wall_angle, bool paper_model)
      : parameters_(parameters), wall_angle_(wall_angle), paper_model_(paper_model) {}
  void on_event(const EventRecord& event);
  void add_to(RunOutput& output) const;

 private:
  PendulumWallsParameters parameters_;
  double wall_angle_;
  bool paper_model_;
  double friction_work_ = 0.0;  // J
  std::uint64_t sliding_impacts_ = 0;
  std::optional<EventKind> previous_;
};

template <PendulumModel model>
struct PendulumBinding {
  using System = BasicPendulumWalls<model>;
  using State = typename System::State;

  static const SceneSchema& schema() { return pendulum_walls_schema(); }
  static bool matches(const Scene& scene) {
    return scene.oscillator == "pendulum_walls" &&
           scene.text("model") == (model == PendulumModel::paper ? "paper" : "newton");
  }
  static System make_system(const Scene& scene) { return System(pendulum_walls_parameters(scene)); }
  static State initial_state(const Scene& scene, const System& system) {
    const double theta = scene.number("initial.theta");
    if (std::fabs(theta) > system.wall_angle())
      throw BadInput("initial.theta", to_text(theta),
                     "the bob would start inside a wall (|theta| > asin(b/l) = " +
                         to_text(system.wall_angle()) + ")");
    State x0{};
    x0[0] = theta;
    x0[1] = scene.number("initial.theta_dot");
    return x0;
  }
  static PendulumMode flight_mode(const System&) { return PendulumMode::free; }
  static double forcing_frequency(const System& system) { return system.parameters().omega; }
  static void admit(const System& system, const Scene&, State& x, PendulumMode& mode) {
    admit_pendulum_state(system.wall_angle(), x, mode);
  }
  static std::string_view mode_name(const System&, PendulumMode mode) {
    return pendulum_mode_name(mode);
  }
  // the pivot's peak acceleration V0·ω reaches g: below it the bob cannot be
  // held on a wall, so no contact phase can exist
  static std::vector<SceneBoundary> boundaries() {
    return {{"contact_boundary", "V0*omega = g: below it no contact phase can exist",
             [](const Scene& at) { return at.number("V0") * at.number("omega") - at.number("g"); }}};
  }
  static PendulumRunTally run_tally(const System& system, const Scene&) {
    return PendulumRunTally(system.parameters(), system.wall_angle(), System::is_paper_model);
  }
  // the impulse, slip, contact force and friction work of every model of the
  // bob; Model P adds its impact residuals (event_extender below)
  static EventColumns event_columns(const System&) {
    if constexpr (System::is_paper_model)
      return {EventColumn::normal_impulse, EventColumn::tangential_velocity,
              EventColumn::normal_force, EventColumn::friction_work,
              EventColumn::instantaneous_residual, EventColumn::sliding_residual};
    else
      return {EventColumn::normal_impulse, EventColumn::tangential_velocity,
              EventColumn::normal_force, EventColumn::friction_work};
  }
  // Model P's impact residuals (PaperImpactResiduals), events.csv's columns for them
  static EventExtender event_extender(const System& system)
    requires System::is_paper_model
  {
    return [system](const EventRecord& event) {
      const PaperImpactResiduals residuals = system.impact_residuals(event);
      return EventExtension{residuals.instantaneous, residuals.sliding};
    };
  }
};

// meta.json's derived quantities of the rigid-body model: the friction work
// and the ratio of tangential velocities after and before each impact (the
// restitution e_t that emerges from the rigid bodies).
class RigidPendulumRunTally {
 public:
  RigidPendulumRunTally(const RigidPendulumWalls& system, double forcing_period, bool spin_free)
      : wall_angle_(system.wall_angle()), ball_inertia_(system.ball_inertia()),
        forcing_period_(forcing_period), spin_free_(spin_free) {}
  void on_event(const EventRecord& event);
  void add_to(RunOutput& output) const;

 private:
  double wall_angle_, ball_inertia_, forcing_period_;
  bool spin_free_;
  double friction_work_ = 0.0;  // J
  std::vector<double> ratios_;
};

// the rigid-body model's parameters: the pendulum's keys and radius, spin;
// BadInput where they do not fit together (radius >= b, spin = free with
// radius = 0)
RigidPendulumParameters rigid_pendulum_parameters(const Scene& scene);

// the ball starts without spin of its own: with a free bearing its absolute
// rate φ̇ is 0, locked it turns with the rod
RigidPendulumWalls::State rigid_pendulum_initial_state(const Scene& scene,
                                                       const RigidPendulumWalls& system);

// A continued state moved into the admissible set: a ball in a contact phase
// (or beyond a moved wall) starts on the wall at rest in free flight, with
// the spin it has where the spin is free; the bookkeeping (φ, W_f) restarts
// from zero.
void admit_rigid_pendulum_state(const RigidPendulumWalls& system, RigidPendulumWalls::State& x,
                                RigidPendulumWalls::Mode& mode);

// One binding per spin: the tangent space is (θ, θ̇) with the spin locked
// and (θ, θ̇, φ̇) with it free (rigid_pendulum_spin.hpp).
template <RigidSpin spin>
struct RigidPendulumBinding {
  using System = RigidPendulumOf<spin>;
  using State = typename System::State;
  using Mode = typename System::Mode;

  static const SceneSchema& schema() { return pendulum_walls_schema(); }
  static bool matches(const Scene& scene) {
    return scene.oscillator == "pendulum_walls" && scene.text("model") == "rigid" &&
           (scene.text("spin") == "free") == (spin == RigidSpin::free);
  }
  static System make_system(const Scene& scene) { return System(rigid_pendulum_parameters(scene)); }
  static State initial_state(const Scene& scene, const System& system) {
    return rigid_pendulum_initial_state(scene, system);
  }
  static Mode flight_mode(const System&) { return Mode::free; }
  static double forcing_frequency(const System& system) { return system.parameters().omega; }
  static void admit(const System& system, const Scene&, State& x, Mode& mode) {
    admit_rigid_pendulum_state(system, x, mode);
  }
  static std::string_view mode_name(const System&, Mode mode) {
    return rigid_pendulum_mode_name(mode);
  }
  // as Model N's: below V0·ω = g the ball cannot be held on a wall
  static std::vector<SceneBoundary> boundaries() {
    return PendulumBinding<PendulumModel::newton>::boundaries();
  }
  static RigidPendulumRunTally run_tally(const System& system, const Scene&) {
    return RigidPendulumRunTally(system, 2.0 * std::numbers::pi / forcing_frequency(system),
                                 system.spin_free());
  }
  // the impulse, slip before and after an impact, contact force and friction work
  static EventColumns event_columns(const System&) {
    return {EventColumn::normal_impulse, EventColumn::tangential_velocity,
            EventColumn::normal_force, EventColumn::friction_work,
            EventColumn::tangential_velocity_after};
  }
};

}  // namespace impactlab
