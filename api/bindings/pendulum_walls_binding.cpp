// The pendulum's scene schema, its parameters read from a scene, and what its
// bindings (pendulum_walls_binding.hpp) do out of line.
#include <impactlab/api/bindings/pendulum_walls_binding.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/oscillators/pendulum_walls/sliding_impact.hpp>
#include <impactlab/platform/sample_median.hpp>

namespace impactlab {

namespace {

// Which model reads which key (read_by, the values of `model`), from the code
// that reads them: every model reads the pendulum's parameters, μ included
// (Models N and P: the impulse's split, the contact's normal force, friction
// work and Painlevé test); e_t is read by Model P's sliding-impact test
// (sliding_impact.hpp) and by the rigid-body model's stick impulse
// (rigid_pendulum_walls.hpp), not by Model N; only the rigid-body model
// reads radius and spin (rigid_pendulum_parameters).
SceneSchema make_pendulum_walls_schema() {
  SceneSchema schema{"pendulum_walls", "theta", common_keys(), "model"};
  const double inf = 1e308;
  std::vector<KeySpec> own = {
      {.key = "model", .help = "impact model: newton (Model N), paper (Model P, the paper's sliding impact), rigid (rod and ball as rigid bodies)",
       .is_text = true, .default_text = "newton", .choices = {"newton", "paper", "rigid"}},
      {.key = "m", .unit = "kg", .help = "bob mass", .default_number = 0.5, .lower = 0.0,
       .upper = inf, .lower_open = true},
      {.key = "l", .unit = "m", .help = "rod length", .default_number = 0.7, .lower = 0.0,
       .upper = inf, .lower_open = true},
      {.key = "b", .unit = "m", .help = "half the distance between the walls (b < l)",
       .default_number = 0.05, .lower = 0.0, .upper = inf, .lower_open = true},
      {.key = "d", .unit = "N m s/rad", .help = "damping at the pivot", .default_number = 0.01,
       .lower = 0.0, .upper = inf},
      {.key = "g", .unit = "m/s^2", .help = "gravity", .default_number = 9.81, .lower = 0.0,
       .upper = inf},
      {.key = "V0", .unit = "m/s", .help = "pivot velocity amplitude", .default_number = 1.5,
       .lower = 0.0, .upper = inf},
      {.key = "omega", .unit = "rad/s", .help = "forcing frequency", .default_number = 7.0,
       .lower = 0.0, .upper = inf, .lower_open = true},
      {.key = "e_n", .help = "normal restitution", .default_number = 0.3, .lower = 0.0,
       .upper = 1.0},
      {.key = "e_t", .help = "tangential restitution, the paper's e_y: slip kept by an impact, -e_t (Model P's sliding-impact test, the rigid model's stick impulse)",
       .default_number = -0.1, .lower = -1.0, .upper = 0.0, .read_by = {"paper", "rigid"}},
      {.key = "mu", .help = "Coulomb friction coefficient", .default_number = 0.6, .lower = 0.0,
       .upper = inf},
      accumulation_tolerance_key(),
      {.key = "initial.theta", .unit = "rad", .help = "initial angle, |theta| <= asin(b/l)",
       .default_number = 0.0, .lower = -inf, .upper = inf},
      {.key = "initial.theta_dot", .unit = "rad/s", .help = "initial angular velocity",
       .default_number = 0.1, .lower = -inf, .upper = inf},
      {.key = "radius", .unit = "m", .help = "ball radius (radius < b)",
       .default_number = 0.0, .lower = 0.0, .upper = inf, .read_by = {"rigid"}},
      {.key = "spin", .help = "ball on a free bearing or fixed to the rod",
       .is_text = true, .default_text = "locked", .choices = {"locked", "free"},
       .read_by = {"rigid"}},
  };
  schema.keys.insert(schema.keys.end(), own.begin(), own.end());
  return schema;
}

}  // namespace

const SceneSchema& pendulum_walls_schema() {
  static const SceneSchema instance = make_pendulum_walls_schema();
  return instance;
}

std::string_view pendulum_mode_name(PendulumMode mode) {
  switch (mode) {
    case PendulumMode::free: return "free";
    case PendulumMode::contact_right: return "contact_right";
    case PendulumMode::contact_left: return "contact_left";
  }
  return "unknown";
}

std::string_view rigid_pendulum_mode_name(RigidPendulumWalls::Mode mode) {
  switch (mode) {
    case RigidPendulumWalls::Mode::free: return "free";
    case RigidPendulumWalls::Mode::slide_right_pos: return "slide_right_pos";
    case RigidPendulumWalls::Mode::slide_right_neg: return "slide_right_neg";
    case RigidPendulumWalls::Mode::slide_left_pos: return "slide_left_pos";
    case RigidPendulumWalls::Mode::slide_left_neg: return "slide_left_neg";
    case RigidPendulumWalls::Mode::stick_right: return "stick_right";
    case RigidPendulumWalls::Mode::stick_left: return "stick_left";
  }
  return "unknown";
}

void PendulumRunTally::on_event(const EventRecord& event) {
  if (event.kind == EventKind::contact_end) friction_work_ = event.friction_work;
  if (event.kind == EventKind::contact_start && previous_ == EventKind::impact) ++sliding_impacts_;
  previous_ = event.kind;
}

void PendulumRunTally::add_to(RunOutput& output) const {
  const PendulumWallsParameters& p = parameters_;
  output.derived = {
      {"theta0_rad", wall_angle_},
      {"mu_tan_theta0", p.mu * std::tan(wall_angle_)},
      {"forcing_period_s", 2.0 * std::numbers::pi / p.omega},
      {"friction_work_J", friction_work_},
  };
  if (paper_model_) {
    output.derived["sliding_impacts"] = sliding_impacts_;
    output.derived["slip_end_velocity_m_per_s"] = slip_end_velocity(p.V0, p.omega, p.g);
  }
}

void RigidPendulumRunTally::on_event(const EventRecord& event) {
  if (event.kind == EventKind::contact_end) friction_work_ = event.friction_work;
  if (event.kind == EventKind::impact && std::fabs(event.tangential_velocity) > 1e-9)
    ratios_.push_back(event.tangential_velocity_after / event.tangential_velocity);
}

void RigidPendulumRunTally::add_to(RunOutput& output) const {
  const auto [lowest, highest] = std::minmax_element(ratios_.begin(), ratios_.end());
  output.derived = {
      {"theta0_rad", wall_angle_},
      {"ball_inertia_kg_m2", ball_inertia_},
      {"spin", spin_free_ ? "free" : "locked"},
      {"forcing_period_s", forcing_period_},
      {"friction_work_J", friction_work_},
      {"tangential_ratio_impacts", ratios_.size()},
      {"tangential_ratio_median", upper_median(ratios_)},
      {"tangential_ratio_min", ratios_.empty() ? NAN : *lowest},
      {"tangential_ratio_max", ratios_.empty() ? NAN : *highest},
      {"emergent_e_t_median", -upper_median(ratios_)},
  };
}

RigidPendulumParameters rigid_pendulum_parameters(const Scene& scene) {
  RigidPendulumParameters rp;
  rp.pendulum = pendulum_walls_parameters(scene);
  const PendulumWallsParameters& p = rp.pendulum;
  rp.radius = scene.number("radius");
  rp.spin_free = scene.text("spin") == "free";
  if (!(rp.radius < p.b))
    throw BadInput("radius", to_text(rp.radius), "the ball must fit between the walls (radius < b)");
  if (rp.spin_free && !(rp.radius > 0.0))
    throw BadInput("spin", "free", "a spinning ball needs radius > 0");
  return rp;
}

RigidPendulumWalls::State rigid_pendulum_initial_state(const Scene& scene,
                                                       const RigidPendulumWalls& system) {
  const double theta = scene.number("initial.theta");
  if (std::fabs(theta) > system.wall_angle())
    throw BadInput("initial.theta", to_text(theta),
                   "the ball would start inside a wall (|theta| > asin((b - radius)/l) = " +
                       to_text(system.wall_angle()) + ")");
  const double theta_dot = scene.number("initial.theta_dot");
  const RigidPendulumWalls::State x0{theta, theta_dot, system.spin_free() ? 0.0 : theta_dot, theta,
                                     0.0};
  // a start on a wall with no motion to go on with (Painlevé) is no scene:
  // the friction coefficient that makes it so is named
  if (system.painleve_on_wall(x0, scene.number("t0")))
    throw BadInput("mu", to_text(scene.number("mu")),
                   "the ball starts on a wall where the contact problem has no solution or "
                   "several (Painlevé): start it off the wall or lower mu");
  return x0;
}

void admit_rigid_pendulum_state(const RigidPendulumWalls& system, RigidPendulumWalls::State& x,
                                RigidPendulumWalls::Mode& mode) {
  using Mode = RigidPendulumWalls::Mode;
  const double wall_angle = system.wall_angle();
  if (mode != Mode::free) {
    x[0] = RigidPendulumWalls::wall_of(mode) * wall_angle;
    x[1] = 0.0;
  }
  if (std::fabs(x[0]) > wall_angle) x[0] = std::copysign(wall_angle, x[0]);
  if (!system.spin_free()) x[RigidPendulumWalls::spin_rate] = x[1];
  x[RigidPendulumWalls::spin_angle] = 0.0;
  x[RigidPendulumWalls::friction_work] = 0.0;
  mode = Mode::free;
}

PendulumWallsParameters pendulum_walls_parameters(const Scene& scene) {
  if (scene.text("integrator.method") == "exact")
    throw BadInput("integrator.method", "exact", "the pendulum has no closed-form flow");
  PendulumWallsParameters p;
  p.m = scene.number("m");
  p.l = scene.number("l");
  p.b = scene.number("b");
  p.d = scene.number("d");
  p.g = scene.number("g");
  p.V0 = scene.number("V0");
  p.omega = scene.number("omega");
  p.e_n = scene.number("e_n");
  p.e_t = scene.number("e_t");
  p.mu = scene.number("mu");
  if (!(p.b < p.l)) throw BadInput("b", to_text(p.b), "the walls must be closer than l (b < l)");
  // the moment of inertia m l^2 divides every rate and every impulse: one
  // that overflows (l = 1e200) gave an infinite impulse at t0 and a run
  // "completed" at an undefined time; the factor at fault is named
  const double inertia = p.m * p.l * p.l;
  if (!(std::isfinite(inertia) && inertia > 0.0)) {
    const double length_squared = p.l * p.l;
    const bool length_at_fault = !(std::isfinite(length_squared) && length_squared > 0.0);
    throw BadInput(length_at_fault ? "l" : "m", to_text(length_at_fault ? p.l : p.m),
                   "the moment of inertia m l^2 = " + to_text(inertia) +
                       " kg m^2 is not a finite positive number");
  }
  // the normal gap per radian at the wall is l cos θ0
  p.accumulation = accumulation_tolerance(scene, 1.0 / p.omega, std::asin(p.b / p.l),
                                          std::sqrt(p.l * p.l - p.b * p.b));
  return p;
}

}  // namespace impactlab
