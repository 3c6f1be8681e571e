#include "api/scene_loading.hpp"

#include "api/oscillator_registry.hpp"

namespace impactlab {

namespace {

const SceneSchema& registered_schema(std::string_view oscillator) {
  return *oscillator_entry(oscillator).schema;
}

}  // namespace

Scene load_scene(std::string_view name_or_path) {
  return read_scene(name_or_path, registered_schema);
}

void apply_override(Scene& scene, std::string_view assignment) {
  set_scene_key(scene, registered_schema(scene.oscillator), assignment);
}

const SceneSchema& scene_schema(const Scene& scene) { return registered_schema(scene.oscillator); }

nlohmann::json scene_record(const Scene& scene) {
  const SceneSchema& schema = scene_schema(scene);
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& spec : schema.keys) {
    const auto& value = scene.values.at(std::string(spec.key));
    nlohmann::json entry;
    if (const auto* number = std::get_if<double>(&value))
      entry["value"] = *number;
    else
      entry["value"] = std::get<std::string>(value);
    if (!spec.unit.empty()) entry["unit"] = spec.unit;
    parameters[std::string(spec.key)] = entry;
  }
  return {{"source", scene.name}, {"oscillator", scene.oscillator}, {"keys", parameters}};
}

}  // namespace impactlab
