// The oscillators the program knows: each one's scene schema, from the
// built-in bindings (api/builtin_bindings.hpp) and the models registered at
// run time.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// An oscillator as the scene loader knows it: its schema (keys, units,
// ranges, help). What runs it is its binding (api/builtin_bindings.hpp,
// reached through api/visit_scene.hpp).
struct OscillatorEntry {
  const SceneSchema* schema;
};

std::span<const OscillatorEntry> oscillators();

// The entry for an oscillator name (built in, or registered at run time from
// a scene file's [model] section); BadInput (key `oscillator`) if unknown.
const OscillatorEntry& oscillator_entry(std::string_view name);

// An oscillator built at run time: its schema, hooks, and the data the hooks
// need (for a [model] section, the compiled model). Registered once per name
// and kept for the life of the program, so references to it stay valid.
struct RuntimeOscillator {
  std::string name;
  SceneSchema schema;
  OscillatorEntry entry{};
  std::shared_ptr<const void> data;
  std::vector<std::unique_ptr<std::string>> texts;  // what schema's string_views point at

  std::string_view keep(std::string text) {
    texts.push_back(std::make_unique<std::string>(std::move(text)));
    return *texts.back();
  }
};

// Registers `oscillator` under its name unless one is there already; returns
// the registered one. Thread-safe.
const RuntimeOscillator& register_runtime_oscillator(std::unique_ptr<RuntimeOscillator> oscillator);

// The runtime oscillator of that name, or nullptr. Thread-safe.
const RuntimeOscillator* runtime_oscillator(std::string_view name);

// Where `name_or_path` is a scene file with a [model] section: builds its
// oscillator (compiled, or found in the cache) and registers it under
// model_oscillator_name(path), once per program. Bad models throw BadInput
// (FILE:LINE:COL: message). Defined with the model binding
// (api/bindings/model_file_binding.cpp).
void register_model_scene(std::string_view name_or_path);

}  // namespace impactlab
