// The oscillators the program knows: each one's scene schema and how to run
// it. Each oscillator registers itself in oscillators/<name>/<name>_scene.cpp.
#pragma once

#include <span>
#include <string_view>

#include "io/run_output.hpp"
#include "io/scene.hpp"

namespace impactlab {

struct OscillatorEntry {
  const SceneSchema* schema;
  // builds the system from a validated scene (further checks that need several
  // keys at once throw BadInput) and runs it
  RunOutput (*run)(const Scene& scene, const RunRequest& request);
};

std::span<const OscillatorEntry> oscillators();

// The entry for an oscillator name; BadInput (key `oscillator`) if unknown.
const OscillatorEntry& oscillator_entry(std::string_view name);

}  // namespace impactlab
