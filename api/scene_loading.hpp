// Scenes as the front ends load them: a built-in name or a file path, read
// with the schema of the oscillator it names from the registry, and `--set`
// assignments checked against that schema. The CLI and the Python module
// both call these, so a key is validated the same way everywhere.
#pragma once

#include <string_view>

#include <impactlab/io/scene.hpp>

namespace impactlab {

// Reads a built-in scene by name or a scene file by path, fills defaults from
// its oscillator's schema, and validates every key and value. Throws BadInput.
Scene load_scene(std::string_view name_or_path);

// Applies `KEY=VALUE` (repeatable --set) and validates again. Throws BadInput.
void apply_override(Scene& scene, std::string_view assignment);

// The schema the scene follows.
const SceneSchema& scene_schema(const Scene& scene);

}  // namespace impactlab
