// The oscillators the program knows: each one's scene schema and how to run
// it. Each oscillator registers itself in api/bindings/<name>_binding.cpp.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// analysis/section.hpp, analysis/periodic.hpp
struct SectionRequest;
struct SectionResult;
struct PeriodicRequest;
struct PeriodicResult;
struct ContinuationJob;  // analysis/continuation.hpp
struct ContinuationJobResult;

struct OscillatorEntry {
  const SceneSchema* schema;
  // builds the system from a validated scene (further checks that need several
  // keys at once throw BadInput) and runs it
  RunOutput (*run)(const Scene& scene, const RunRequest& request);
  // the same system onto a Poincaré section (transient, section points, final
  // state for continuation, counts, optional Lyapunov exponent): the analysis
  // layer's entry point (analysis/run_section.hpp)
  SectionResult (*section)(const Scene& scene, const SectionRequest& request) = nullptr;
  // Newton shooting for a period-n orbit and its Floquet multipliers
  // (analysis/run_periodic.hpp)
  PeriodicResult (*periodic_orbit)(const Scene& scene, const PeriodicRequest& request) = nullptr;
  // pseudo-arclength continuation of a period-n orbit in one scene key, its
  // bifurcations and grazing points (analysis/run_continuation.hpp)
  ContinuationJobResult (*continuation)(const Scene& scene, const ContinuationJob& job) = nullptr;
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
