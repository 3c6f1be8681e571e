// Which keys a scene's model reads. A schema whose models read different keys
// names the key that picks the model (SceneSchema::selector, the pendulum's
// `model`) and, beside each key that only some models read, those models
// (KeySpec::read_by), where its binding declares the keys. A key the scene's
// model does not read changes nothing in its runs: sweeping, mapping or
// continuing one is refused; setting one is allowed with a warning.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <impactlab/io/scene.hpp>

namespace impactlab {

// The values of the schema's selector whose model reads `spec`: its read_by,
// else every choice of the selector; empty in a schema without a selector.
std::vector<std::string_view> models_reading(const SceneSchema& schema, const KeySpec& spec);

// The models as a message names them, separated as choices are: "newton|paper".
std::string model_names(const std::vector<std::string_view>& models);

// Why the scene's model does not read `key`: "model = newton does not read
// e_t (read by model = paper|rigid)"; empty where it reads it (every key of a
// schema without a selector; a key the schema does not declare, which
// validation refuses on its own).
std::string unread_key_reason(const Scene& scene, const SceneSchema& schema,
                              std::string_view key);

// Refuses a key to sweep, map or continue that the scene's model does not
// read: BadInput(option, key, unread_key_reason), the option named by its own
// name (`param`, `param2`, `x`, `y`).
void refuse_unread_key(const Scene& scene, const SceneSchema& schema, const std::string& key,
                       const std::string& option);

// The warnings for the keys a user set (`--set`, Python's keywords) that the
// scene's model does not read, one per key however often it was set, in the
// order of `keys`: "e_t = 0.2: model = newton does not read e_t (read by
// model = paper); the value changes nothing". The run goes on.
std::vector<std::string> unread_key_warnings(const Scene& scene, const SceneSchema& schema,
                                             const std::vector<std::string>& keys);

}  // namespace impactlab
