// A scene written back as a scene file: every key of its schema with its
// resolved value, so that loading the file gives the same scene (the same
// values, bit for bit). A scene of a model file keeps that file's [model]
// section. Python's Scene.to_toml() and Scene.save(path) are this.
#pragma once

#include <filesystem>
#include <string>

#include <impactlab/io/scene.hpp>

namespace impactlab {

// The scene file's text: a header comment, then each key of `schema` in its
// order as `key = value  # [unit] help` (dotted keys as TOML dotted keys),
// then the [model] section of a model file's scene.
std::string scene_file_text(const Scene& scene, const SceneSchema& schema);

// Writes scene_file_text to `path` whole or not at all (OutputError where it
// cannot be written).
void save_scene_file(const Scene& scene, const SceneSchema& schema,
                     const std::filesystem::path& path);

}  // namespace impactlab
