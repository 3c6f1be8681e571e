// The bouncing ball's scene schema and runner.
#include <cmath>
#include <numbers>

#include <impactlab/analysis/run_continuation.hpp>
#include <impactlab/analysis/run_periodic.hpp>
#include <impactlab/analysis/run_section.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/run_system.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>

namespace impactlab {

namespace {

SceneSchema make_schema() {
  SceneSchema schema{"bouncing_ball", "y", common_keys()};
  const double inf = 1e308;
  std::vector<KeySpec> own = {
      {.key = "g", .unit = "m/s^2", .help = "gravity", .default_number = 9.81, .lower = 0.0,
       .upper = inf, .lower_open = true},
      {.key = "A", .unit = "m", .help = "table amplitude", .default_number = 0.0112,
       .lower = 0.0, .upper = inf},
      {.key = "omega", .unit = "rad/s", .help = "table angular frequency", .default_number = 30.0,
       .lower = 0.0, .upper = inf, .lower_open = true},
      {.key = "r", .help = "coefficient of restitution", .default_number = 0.8, .lower = 0.0,
       .upper = 1.0},
      accumulation_tolerance_key(),
      {.key = "initial.y", .unit = "m", .help = "initial height, on or above the table",
       .default_number = 0.05, .lower = -inf, .upper = inf},
      {.key = "initial.y_dot", .unit = "m/s", .help = "initial velocity", .default_number = 0.0,
       .lower = -inf, .upper = inf},
  };
  schema.keys.insert(schema.keys.end(), own.begin(), own.end());
  return schema;
}

const SceneSchema& schema() {
  static const SceneSchema instance = make_schema();
  return instance;
}

std::string_view mode_name(BouncingBall::Mode mode) {
  return mode == BouncingBall::Mode::free ? "free" : "stuck";
}

// The system a scene describes.
BouncingBall make_system(const Scene& scene) {
  BouncingBallParameters p;
  p.g = scene.number("g");
  p.A = scene.number("A");
  p.omega = scene.number("omega");
  p.r = scene.number("r");
  p.accumulation = accumulation_tolerance(scene, 1.0 / p.omega, p.A);
  return BouncingBall(p);
}

BouncingBall::State initial_state(const Scene& scene, const BouncingBall& system) {
  const double y = scene.number("initial.y");
  const double table = system.table_position(scene.number("t0"));
  if (y < table)
    throw BadInput("initial.y", to_text(y),
                   "starts below the table (z(t0) = " + to_text(table) + " m)");
  return {y, scene.number("initial.y_dot")};
}

RunOutput run(const Scene& scene, const RunRequest& request) {
  const BouncingBall system = make_system(scene);
  return run_system(system, initial_state(scene, system), BouncingBall::Mode::free, scene,
                    request, 2.0 * std::numbers::pi / system.parameters().omega, mode_name);
}

SectionResult section(const Scene& scene, const SectionRequest& request) {
  const BouncingBall system = make_system(scene);
  const double t0 = scene.number("t0");
  // a continued state starts at t0: below the table (which moved with the
  // parameters) or riding on it, it starts on the table with its velocity
  auto admissible = [&system, t0](BouncingBall::State& x, BouncingBall::Mode& mode) {
    if (x[0] < system.table_position(t0) || mode == BouncingBall::Mode::stuck) {
      x = {system.table_position(t0), system.table_velocity(t0)};
      mode = BouncingBall::Mode::free;
    }
  };
  // a continued run does not start from the scene's initial state (which a
  // swept table amplitude may have put below the table)
  const BouncingBall::State x0 = request.start ? BouncingBall::State{} : initial_state(scene, system);
  return run_section(system, x0, BouncingBall::Mode::free, scene, request,
                     system.parameters().omega, admissible);
}

PeriodicResult periodic_orbit(const Scene& scene, const PeriodicRequest& request) {
  const BouncingBall system = make_system(scene);
  return run_periodic(system, initial_state(scene, system), BouncingBall::Mode::free, scene,
                      request, system.parameters().omega);
}

ContinuationJobResult continuation(const Scene& scene, const ContinuationJob& job) {
  const BouncingBall system = make_system(scene);
  const BouncingBall::State x0 = job.has_start ? BouncingBall::State{} : initial_state(scene, system);
  return run_continuation<BouncingBall>(&make_system, BouncingBall::Mode::free, x0, scene, job);
}

}  // namespace

const OscillatorEntry& bouncing_ball_entry() {
  static const OscillatorEntry entry{&schema(), &run, &section, &periodic_orbit, &continuation};
  return entry;
}

}  // namespace impactlab
