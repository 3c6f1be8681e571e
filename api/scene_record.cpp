#include <impactlab/api/scene_record.hpp>

#include <impactlab/api/model_keys.hpp>
#include <impactlab/api/scene_loading.hpp>

namespace impactlab {

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
    // a key the scene's model does not read changes nothing in its runs
    if (!unread_key_reason(scene, schema, spec.key).empty()) entry["read"] = false;
    parameters[std::string(spec.key)] = entry;
  }
  return {{"source", scene.name}, {"oscillator", scene.oscillator}, {"keys", parameters}};
}

}  // namespace impactlab
