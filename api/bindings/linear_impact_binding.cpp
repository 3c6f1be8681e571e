// The linear impact oscillator's scene schema and system (linear_impact_binding.hpp).
#include <impactlab/api/bindings/linear_impact_binding.hpp>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

SceneSchema make_linear_impact_schema() {
  SceneSchema schema{"linear_impact", "x", common_keys()};
  const double inf = 1e308;
  std::vector<KeySpec> own = {
      {.key = "zeta", .help = "damping ratio", .default_number = 0.05, .lower = 0.0, .upper = inf},
      {.key = "A", .unit = "length", .help = "forcing amplitude", .default_number = 1.0,
       .lower = -inf, .upper = inf},
      {.key = "omega", .help = "forcing frequency over the natural frequency",
       .default_number = 2.0, .lower = 0.0, .upper = inf, .lower_open = true},
      {.key = "sigma", .unit = "length", .help = "position of the stop", .default_number = 0.2,
       .lower = -inf, .upper = inf},
      {.key = "r", .help = "coefficient of restitution", .default_number = 0.8, .lower = 0.0,
       .upper = 1.0},
      accumulation_tolerance_key(),
      {.key = "initial.x", .unit = "length", .help = "initial position, x <= sigma",
       .default_number = 0.0, .lower = -inf, .upper = inf},
      {.key = "initial.x_dot", .unit = "length/time", .help = "initial velocity",
       .default_number = 0.0, .lower = -inf, .upper = inf},
  };
  schema.keys.insert(schema.keys.end(), own.begin(), own.end());
  return schema;
}

}  // namespace

const SceneSchema& linear_impact_schema() {
  static const SceneSchema instance = make_linear_impact_schema();
  return instance;
}

// The system a scene describes (checks that need several keys at once throw BadInput).
LinearImpact LinearImpactBinding::make_system(const Scene& scene) {
  LinearImpactParameters p;
  p.zeta = scene.number("zeta");
  p.A = scene.number("A");
  p.omega = scene.number("omega");
  p.sigma = scene.number("sigma");
  p.r = scene.number("r");
  p.accumulation = accumulation_tolerance(scene, 1.0 / p.omega, p.sigma);
  if (scene.text("integrator.method") == "exact" && !LinearImpact::has_exact_flow(p))
    throw BadInput("zeta", to_text(p.zeta),
                   "method = exact needs an underdamped, non-resonant oscillator (zeta < 1, and "
                   "omega != 1 when zeta = 0)");
  return LinearImpact(p);
}

LinearImpact::State LinearImpactBinding::initial_state(const Scene& scene,
                                                       const LinearImpact& system) {
  const double x = scene.number("initial.x");
  if (x > system.parameters().sigma)
    throw BadInput("initial.x", to_text(x),
                   "starts beyond the stop sigma = " + to_text(system.parameters().sigma));
  return {x, scene.number("initial.x_dot")};
}

}  // namespace impactlab
