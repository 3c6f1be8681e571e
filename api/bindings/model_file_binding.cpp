// Oscillators defined in a scene file's [model] section: a schema built at run
// time from the model's parameters (defaults, units, ranges: the scene keys
// and --set keys) and states (initial.<state>), registered once per model,
// and the bindings of its systems (model_file_binding.hpp).
#include <impactlab/api/bindings/model_file_binding.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/toml_nesting.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>

namespace impactlab {

namespace {

const CompiledModel* loaded_model(const Scene& scene) {
  const RuntimeOscillator* runtime = runtime_oscillator(scene.oscillator);
  return runtime ? static_cast<const CompiledModel*>(runtime->data.get()) : nullptr;
}

// The built-in scenes' checks, for a model: every Newton restitution in
// [0, 1] (named by its parameter where it is one), and the initial state
// outside every wall (its witness on the free side: positive for a falling
// witness, negative for a rising one; named by the state the witness depends
// on most).
template <std::size_t N>
void check_walls_at_start(const ModelSystem<N>& system, const typename ModelSystem<N>::State& x,
                          double t0) {
  const CompiledModel& model = system.model();
  const std::vector<double>& p = system.parameters().values;
  for (std::size_t k = 0; k < model.walls.size(); ++k) {
    const CompiledWall& wall = model.walls[k];
    const std::string restitution_key = fmt::format("model.walls[{}].reset.restitution", k);
    for (const ExpressionText& text : model.written_expressions) {
      if (text.key != restitution_key) continue;
      double after[N + 1];
      model.reset[k](x.data(), t0, p.data(), after);
      const double restitution = after[model.states.size()];
      if (restitution >= 0.0 && restitution <= 1.0) continue;
      const bool is_parameter =
          std::any_of(model.parameters.begin(), model.parameters.end(),
                      [&](const ModelParameter& parameter) { return parameter.name == text.text; });
      throw BadInput(is_parameter ? text.text : restitution_key, fmt::format("{}", restitution),
                     fmt::format("the restitution of wall '{}' must lie in [0, 1]", wall.name));
    }
    double gap[2];
    model.gap[k](x.data(), t0, p.data(), gap);
    const bool inside = wall.direction == TriggerDirection::falling ? gap[0] < 0.0 : gap[0] > 0.0;
    if (!inside) continue;
    double gradient[N];
    model.gap_gradient[k](x.data(), t0, p.data(), gradient);
    std::size_t most = 0;
    for (std::size_t i = 1; i < model.states.size(); ++i)
      if (std::fabs(gradient[i]) > std::fabs(gradient[most])) most = i;
    throw BadInput("initial." + model.states[most], fmt::format("{}", x[most]),
                   fmt::format("starts inside wall '{}': its witness is {} at the initial state, "
                               "free where it is {}",
                               wall.name, gap[0],
                               wall.direction == TriggerDirection::falling ? "positive" : "negative"));
  }
}

}  // namespace

template <std::size_t N>
bool ModelFileBinding<N>::matches(const Scene& scene) {
  const CompiledModel* model = loaded_model(scene);
  // two states run as ModelSystem<2>, three or four as ModelSystem<4>
  return model && (model->states.size() == 2) == (N == 2);
}

template <std::size_t N>
ModelSystem<N> ModelFileBinding<N>::make_system(const Scene& scene) {
  const RuntimeOscillator* runtime = runtime_oscillator(scene.oscillator);
  auto model = std::static_pointer_cast<const CompiledModel>(runtime->data);
  // the Taylor stepper runs the model's series programs, where it has them
  if (!model->series_refusal.empty())
    for (const std::string key : {"integrator.method", "integrator.classification_method"})
      if (scene.text(key) == "taylor")
        throw BadInput(key, "taylor",
                       fmt::format("this model has no Taylor series ({}): the inverse "
                                   "trigonometric functions and powers with a variable "
                                   "exponent have none here; choose rkf78, dopri5, rk8pd or "
                                   "bulirsch_stoer",
                                   model->series_refusal));
  std::vector<double> p;
  for (const auto& parameter : model->parameters) p.push_back(scene.number(parameter.name));
  ModelSystem<N> probe(model, p);
  // held to the scene's accumulation standard on the forcing's time scale;
  // the gap's resolution per unit wall coordinate (ModelSystem scales it)
  return ModelSystem<N>(model, std::move(p),
                        accumulation_tolerance(scene, 1.0 / probe.forcing_frequency(), 1.0));
}

// The scene's initial state, checked: every written expression finite there.
template <std::size_t N>
typename ModelSystem<N>::State ModelFileBinding<N>::initial_state(const Scene& scene,
                                                                 const ModelSystem<N>& system) {
  typename ModelSystem<N>::State x{};
  std::vector<double> values;
  for (std::size_t i = 0; i < N; ++i) {
    x[i] = scene.number("initial." + system.model().states[i]);
    values.push_back(x[i]);
  }
  check_initial_values(system.model(), values, scene.number("t0"), system.parameters().values);
  if (!(system.forcing_frequency() > 0.0) || !(system.max_step() > 0.0))
    throw BadInput("model.forcing_frequency", fmt::format("{}", system.forcing_frequency()),
                   "the forcing frequency and max_step must be positive");
  check_walls_at_start(system, x, scene.number("t0"));
  return x;
}

// Why a model has no linearisation the analyses may use, or empty. A
// sticking mode pins the whole state (ModelSystem::pinned, the collapse at an
// accumulation): right for one degree of freedom, wrong where other states
// move on while one wall holds its mass.
template <std::size_t N>
std::string ModelFileBinding<N>::without_linearisation(const ModelSystem<N>& system) {
  const CompiledModel& model = system.model();
  if (N == 2) return {};
  for (const auto& wall : model.walls)
    if (wall.has_sticking)
      return fmt::format("a {}-state model with a sticking wall: its contact phases have no "
                         "linearisation (Floquet, Lyapunov, continuation)",
                         N);
  return {};
}

template <std::size_t N>
std::string ModelFileBinding<N>::stop_advice(const ModelSystem<N>& system,
                                             const RunOutput& output) {
  if (output.termination != Termination::no_progress || !output.last_event ||
      output.last_event->kind != EventKind::impact)
    return {};
  for (const auto& wall : system.model().walls)
    if (wall.side == output.last_event->wall && !wall.has_sticking)
      return fmt::format(
          "impacts accumulate on wall {} (side {:+d}) and it has no sticking mode: give it a "
          "[model.walls.sticking] table, the state at rest on it (docs/extending.md, \"The model "
          "section\")",
          wall.name, wall.side);
  return {};
}

template struct ModelFileBinding<2>;
template struct ModelFileBinding<4>;

namespace {

void build_schema(RuntimeOscillator& oscillator, const CompiledModel& model) {
  SceneSchema& schema = oscillator.schema;
  schema.oscillator = oscillator.name;
  schema.main_coordinate = oscillator.keep(model.states[0]);
  schema.keys = common_keys();
  // a model file has no closed-form flow: no exact method, for a run or a
  // classification (taylor is refused when the system is made, for a model
  // without series, with the reason)
  for (auto& key : schema.keys)
    if (key.key == "integrator.method" || key.key == "integrator.classification_method")
      std::erase_if(key.choices, [](std::string_view method) { return method == "exact"; });
  schema.keys.push_back(accumulation_tolerance_key());
  for (const auto& parameter : model.parameters)
    schema.keys.push_back({.key = oscillator.keep(parameter.name),
                           .unit = oscillator.keep(parameter.unit),
                           .help = oscillator.keep(parameter.help),
                           .default_number = parameter.default_value,
                           .lower = parameter.lower,
                           .upper = parameter.upper,
                           .lower_open = parameter.lower_open,
                           .upper_open = parameter.upper_open});
  for (const auto& state : model.states)
    schema.keys.push_back({.key = oscillator.keep("initial." + state),
                           .help = "initial value of the state",
                           .default_number = 0.0});
}

}  // namespace

void register_model_scene(std::string_view name_or_path) {
  const std::string path(name_or_path);
  const std::string name = model_oscillator_name(path);
  std::error_code ignored;
  if (runtime_oscillator(name) || !std::filesystem::is_regular_file(path, ignored)) return;
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  toml::table document;
  try {
    document = parse_bounded_toml(text.str(), path);
  } catch (const toml::parse_error&) {
    return;  // read_scene reports it
  }
  // `model = "newton"` is the pendulum's impact model, not a model section
  const toml::node* model_table = document.get("model");
  if (!model_table || !model_table->is_table()) return;
  const ModelDefinition definition = read_model_definition(*model_table->as_table(), path);
  std::shared_ptr<const CompiledModel> model =
      compile_model(definition, compile_options_from_environment());
  if (!model->compiled)
    std::cerr << "impactlab: model " << path << ": " << model->slow_path_reason
              << "; using the interpreted evaluator (the slow path, several times slower)\n";
  else if (!model->cache_note.empty())
    std::cerr << "impactlab: model " << path << ": " << model->cache_note << "\n";

  auto oscillator = std::make_unique<RuntimeOscillator>();
  oscillator->name = name;
  build_schema(*oscillator, *model);
  oscillator->entry = {&oscillator->schema};
  oscillator->data = model;
  register_runtime_oscillator(std::move(oscillator));
}

}  // namespace impactlab
