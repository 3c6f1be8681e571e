// The linear impact oscillator's scene schema and runner.
#include <numbers>

#include <impactlab/analysis/run_continuation.hpp>
#include <impactlab/analysis/run_periodic.hpp>
#include <impactlab/analysis/run_section.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/run_system.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>

namespace impactlab {

namespace {

SceneSchema make_schema() {
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

const SceneSchema& schema() {
  static const SceneSchema instance = make_schema();
  return instance;
}

std::string_view mode_name(LinearImpact::Mode mode) {
  return mode == LinearImpact::Mode::free ? "free" : "stuck";
}

// The system a scene describes (checks that need several keys at once throw BadInput).
LinearImpact make_system(const Scene& scene) {
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

LinearImpact::State initial_state(const Scene& scene, const LinearImpact& system) {
  const double x = scene.number("initial.x");
  if (x > system.parameters().sigma)
    throw BadInput("initial.x", to_text(x),
                   "starts beyond the stop sigma = " + to_text(system.parameters().sigma));
  return {x, scene.number("initial.x_dot")};
}

RunOutput run(const Scene& scene, const RunRequest& request) {
  const LinearImpact system = make_system(scene);
  const double omega = system.parameters().omega;
  return run_system(system, initial_state(scene, system), LinearImpact::Mode::free, scene, request,
                    2.0 * std::numbers::pi / omega, mode_name);
}

SectionResult section(const Scene& scene, const SectionRequest& request) {
  const LinearImpact system = make_system(scene);
  const double sigma = system.parameters().sigma;
  // a continued state beyond a moved stop starts on it
  auto admissible = [sigma](LinearImpact::State& x, LinearImpact::Mode& mode) {
    if (x[0] > sigma || mode == LinearImpact::Mode::stuck) {
      x = {sigma, 0.0};
      mode = LinearImpact::Mode::free;
    }
  };
  // a continued run does not start from the scene's initial state (which a
  // swept sigma may have left beyond the stop)
  const LinearImpact::State x0 = request.start ? LinearImpact::State{} : initial_state(scene, system);
  return run_section(system, x0, LinearImpact::Mode::free, scene, request,
                     system.parameters().omega, admissible);
}

PeriodicResult periodic_orbit(const Scene& scene, const PeriodicRequest& request) {
  const LinearImpact system = make_system(scene);
  return run_periodic(system, initial_state(scene, system), LinearImpact::Mode::free, scene,
                      request, system.parameters().omega);
}

ContinuationJobResult continuation(const Scene& scene, const ContinuationJob& job) {
  const LinearImpact system = make_system(scene);
  const LinearImpact::State x0 = job.has_start ? LinearImpact::State{} : initial_state(scene, system);
  return run_continuation<LinearImpact>(&make_system, LinearImpact::Mode::free, x0, scene, job);
}

}  // namespace

const OscillatorEntry& linear_impact_entry() {
  static const OscillatorEntry entry{&schema(), &run, &section, &periodic_orbit, &continuation};
  return entry;
}

}  // namespace impactlab
