// The pendulum's scene schema and runner.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>

#include <impactlab/analysis/run_continuation.hpp>
#include <impactlab/analysis/run_periodic.hpp>
#include <impactlab/analysis/run_section.hpp>
#include <impactlab/api/bindings/pendulum_walls_parameters.hpp>
#include <impactlab/api/bindings/rigid_pendulum_binding.hpp>
#include <impactlab/api/event_tap.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/run_system.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace impactlab {

namespace {

SceneSchema make_schema() {
  SceneSchema schema{"pendulum_walls", "theta", common_keys()};
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
      {.key = "e_t", .help = "tangential restitution e_y of Model P", .default_number = -0.1,
       .lower = -1.0, .upper = 0.0},
      {.key = "mu", .help = "Coulomb friction coefficient", .default_number = 0.6, .lower = 0.0,
       .upper = inf},
      accumulation_tolerance_key(),
      {.key = "initial.theta", .unit = "rad", .help = "initial angle, |theta| <= asin(b/l)",
       .default_number = 0.0, .lower = -inf, .upper = inf},
      {.key = "initial.theta_dot", .unit = "rad/s", .help = "initial angular velocity",
       .default_number = 0.1, .lower = -inf, .upper = inf},
      {.key = "radius", .unit = "m", .help = "ball radius (model rigid; radius < b)",
       .default_number = 0.0, .lower = 0.0, .upper = inf},
      {.key = "spin", .help = "ball on a free bearing or fixed to the rod (model rigid)",
       .is_text = true, .default_text = "locked", .choices = {"locked", "free"}},
  };
  schema.keys.insert(schema.keys.end(), own.begin(), own.end());
  return schema;
}

const SceneSchema& schema() {
  static const SceneSchema instance = make_schema();
  return instance;
}

std::string_view mode_name(PendulumMode mode) {
  switch (mode) {
    case PendulumMode::free: return "free";
    case PendulumMode::contact_right: return "contact_right";
    case PendulumMode::contact_left: return "contact_left";
  }
  return "unknown";
}

template <class System>
typename System::State initial_state(const Scene& scene, const System& system) {
  const double theta = scene.number("initial.theta");
  if (std::fabs(theta) > system.wall_angle())
    throw BadInput("initial.theta", to_text(theta),
                   "the bob would start inside a wall (|theta| > asin(b/l) = " +
                       to_text(system.wall_angle()) + ")");
  typename System::State x0{};
  x0[0] = theta;
  x0[1] = scene.number("initial.theta_dot");
  return x0;
}

// The rigid-body model runs through its own scene code and has no section
// hook yet.
void reject_rigid_analysis(const Scene& scene) {
  if (scene.text("model") == "rigid")
    throw BadInput("model", "rigid",
                   "sections, sweeps and periodic orbits take newton or paper in this version");
}

template <class System>
SectionResult section_model(const Scene& scene, const SectionRequest& request) {
  const System system(pendulum_walls_parameters(scene));
  const double theta0 = system.wall_angle();
  // a continued state beyond a moved wall, or resting on a wall, starts on
  // the wall at rest in free flight (the event at t0 decides contact again);
  // the friction work (and Model P's pending release rate) restart from zero
  // at each parameter value
  auto admissible = [theta0](typename System::State& x, PendulumMode& mode) {
    if (mode != PendulumMode::free) {
      x[0] = mode == PendulumMode::contact_right ? theta0 : -theta0;
      x[1] = 0.0;
    }
    if (std::fabs(x[0]) > theta0) x[0] = std::copysign(theta0, x[0]);
    for (std::size_t i = 2; i < x.size(); ++i) x[i] = 0.0;
    mode = PendulumMode::free;
  };
  // a continued run does not start from the scene's initial state (which a
  // swept b may have put inside a wall)
  const typename System::State x0 =
      request.start ? typename System::State{} : initial_state(scene, system);
  return run_section(system, x0, PendulumMode::free, scene, request, system.parameters().omega,
                     admissible);
}

SectionResult section(const Scene& scene, const SectionRequest& request) {
  reject_rigid_analysis(scene);
  if (scene.text("model") == "paper") return section_model<PaperPendulumWalls>(scene, request);
  return section_model<PendulumWalls>(scene, request);
}

PeriodicResult periodic_orbit(const Scene& scene, const PeriodicRequest& request) {
  reject_rigid_analysis(scene);
  if (scene.text("model") == "paper") {
    const PaperPendulumWalls system(pendulum_walls_parameters(scene));
    return run_periodic(system, initial_state(scene, system), PendulumMode::free, scene, request,
                        system.parameters().omega);
  }
  const PendulumWalls system(pendulum_walls_parameters(scene));
  return run_periodic(system, initial_state(scene, system), PendulumMode::free, scene, request,
                      system.parameters().omega);
}

template <class System>
ContinuationJobResult continuation_model(const Scene& scene, const ContinuationJob& job) {
  const System system(pendulum_walls_parameters(scene));
  const typename System::State x0 =
      job.has_start ? typename System::State{} : initial_state(scene, system);
  auto system_at = [](const Scene& at) { return System(pendulum_walls_parameters(at)); };
  // the pivot's peak acceleration V0·ω reaches g: below it the bob cannot be
  // held on a wall, so no contact phase can exist
  const std::vector<SceneBoundary> boundaries = {
      {"contact_boundary", "V0*omega = g: below it no contact phase can exist",
       [](const Scene& at) { return at.number("V0") * at.number("omega") - at.number("g"); }}};
  return run_continuation<System>(system_at, PendulumMode::free, x0, scene, job, boundaries);
}

ContinuationJobResult continuation(const Scene& scene, const ContinuationJob& job) {
  reject_rigid_analysis(scene);
  if (scene.text("model") == "paper") return continuation_model<PaperPendulumWalls>(scene, job);
  return continuation_model<PendulumWalls>(scene, job);
}

template <PendulumModel model>
RunOutput run_model(const Scene& scene, const RunRequest& request) {
  using System = BasicPendulumWalls<model>;
  const System system(pendulum_walls_parameters(scene));
  const PendulumWallsParameters& p = system.parameters();
  const typename System::State x0 = initial_state(scene, system);
  const double period = 2.0 * std::numbers::pi / p.omega;

  // the derived quantities, tallied as the events pass (kept or streamed)
  double friction_work = 0.0;
  std::uint64_t sliding_impacts = 0;
  std::optional<EventKind> previous;
  EventTap tally(
      [&](const EventRecord& event) {
        if (event.kind == EventKind::contact_end) friction_work = event.friction_work;
        // a sliding impact: a contact phase that starts at an impact, not at
        // the accumulation point of a chatter
        if (event.kind == EventKind::contact_start && previous == EventKind::impact)
          ++sliding_impacts;
        previous = event.kind;
      },
      request.event_sink);
  RunRequest tallied = request;
  tallied.event_sink = &tally;
  RunOutput output = run_system(system, x0, PendulumMode::free, scene, tallied, period, mode_name);
  output.derived = {
      {"theta0_rad", system.wall_angle()},
      {"mu_tan_theta0", p.mu * std::tan(system.wall_angle())},
      {"forcing_period_s", period},
      {"friction_work_J", friction_work},
  };
  if constexpr (System::is_paper_model) {
    output.derived["sliding_impacts"] = sliding_impacts;
    output.derived["slip_end_velocity_m_per_s"] = slip_end_velocity(p.V0, p.omega, p.g);
  }
  return output;
}

RunOutput run(const Scene& scene, const RunRequest& request) {
  const std::string& model = scene.text("model");
  if (model == "rigid") return run_rigid_pendulum(scene, request);
  if (model == "paper") return run_model<PendulumModel::paper>(scene, request);
  return run_model<PendulumModel::newton>(scene, request);
}

}  // namespace

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
  // the normal gap per radian at the wall is l cos θ0
  p.accumulation = accumulation_tolerance(scene, 1.0 / p.omega, std::asin(p.b / p.l),
                                          std::sqrt(p.l * p.l - p.b * p.b));
  return p;
}

const OscillatorEntry& pendulum_walls_entry() {
  static const OscillatorEntry entry{&schema(), &run, &section, &periodic_orbit, &continuation};
  return entry;
}

}  // namespace impactlab
