#include <impactlab/api/model_keys.hpp>

#include <algorithm>
#include <set>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/message_text.hpp>

namespace impactlab {

namespace {

const KeySpec* declared_key(const SceneSchema& schema, std::string_view key) {
  const auto spec = std::find_if(schema.keys.begin(), schema.keys.end(),
                                 [&](const KeySpec& k) { return k.key == key; });
  return spec == schema.keys.end() ? nullptr : &*spec;
}

}  // namespace

std::vector<std::string_view> models_reading(const SceneSchema& schema, const KeySpec& spec) {
  if (schema.selector.empty()) return {};
  if (!spec.read_by.empty()) return spec.read_by;
  const KeySpec* selector = declared_key(schema, schema.selector);
  return selector == nullptr ? std::vector<std::string_view>{} : selector->choices;
}

std::string model_names(const std::vector<std::string_view>& models) {
  std::string text;
  for (std::size_t i = 0; i < models.size(); ++i)
    text += (i == 0 ? "" : "|") + std::string(models[i]);
  return text;
}

std::string unread_key_reason(const Scene& scene, const SceneSchema& schema,
                              std::string_view key) {
  const KeySpec* spec = declared_key(schema, key);
  if (schema.selector.empty() || spec == nullptr || spec->read_by.empty()) return "";
  const std::string& model = scene.text(std::string(schema.selector));
  if (std::find(spec->read_by.begin(), spec->read_by.end(), model) != spec->read_by.end())
    return "";
  return std::string(schema.selector) + " = " + model + " does not read " + std::string(key) +
         " (read by " + std::string(schema.selector) + " = " + model_names(spec->read_by) + ")";
}

void refuse_unread_key(const Scene& scene, const SceneSchema& schema, const std::string& key,
                       const std::string& option) {
  const std::string reason = unread_key_reason(scene, schema, key);
  if (!reason.empty()) throw BadInput(option, key, reason);
}

std::vector<std::string> unread_key_warnings(const Scene& scene, const SceneSchema& schema,
                                             const std::vector<std::string>& keys) {
  std::vector<std::string> warnings;
  std::set<std::string> warned;
  for (const std::string& key : keys) {
    const std::string reason = unread_key_reason(scene, schema, key);
    if (reason.empty() || !warned.insert(key).second) continue;
    warnings.push_back(elide_value(key) + " = " + elide_value(to_text(scene.values.at(key))) +
                       ": " + reason + "; the value changes nothing");
  }
  return warnings;
}

}  // namespace impactlab
