// The bouncing ball's scene schema and system (bouncing_ball_binding.hpp).
#include <impactlab/api/bindings/bouncing_ball_binding.hpp>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

SceneSchema make_bouncing_ball_schema() {
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

}  // namespace

const SceneSchema& bouncing_ball_schema() {
  static const SceneSchema instance = make_bouncing_ball_schema();
  return instance;
}

BouncingBall BouncingBallBinding::make_system(const Scene& scene) {
  BouncingBallParameters p;
  p.g = scene.number("g");
  p.A = scene.number("A");
  p.omega = scene.number("omega");
  p.r = scene.number("r");
  p.accumulation = accumulation_tolerance(scene, 1.0 / p.omega, p.A);
  return BouncingBall(p);
}

BouncingBall::State BouncingBallBinding::initial_state(const Scene& scene,
                                                       const BouncingBall& system) {
  const double y = scene.number("initial.y");
  const double table = system.table_position(scene.number("t0"));
  if (y < table)
    throw BadInput("initial.y", to_text(y),
                   "starts below the table (z(t0) = " + to_text(table) + " m)");
  return {y, scene.number("initial.y_dot")};
}

}  // namespace impactlab
