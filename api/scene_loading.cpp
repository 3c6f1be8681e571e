#include <impactlab/api/scene_loading.hpp>

#include <impactlab/api/oscillator_registry.hpp>

namespace impactlab {

namespace {

const SceneSchema& registered_schema(std::string_view oscillator) {
  return *oscillator_entry(oscillator).schema;
}

}  // namespace

Scene load_scene(std::string_view name_or_path) {
  register_model_scene(name_or_path);
  return read_scene(name_or_path, registered_schema);
}

void apply_override(Scene& scene, std::string_view assignment) {
  set_scene_key(scene, registered_schema(scene.oscillator), assignment);
}

const SceneSchema& scene_schema(const Scene& scene) { return registered_schema(scene.oscillator); }

}  // namespace impactlab
