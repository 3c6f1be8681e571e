// The scene as every meta.json records it: its source, its oscillator and
// every key with its value and unit.
#pragma once

#include <nlohmann/json.hpp>

#include <impactlab/io/scene.hpp>

namespace impactlab {

nlohmann::json scene_record(const Scene& scene);

}  // namespace impactlab
