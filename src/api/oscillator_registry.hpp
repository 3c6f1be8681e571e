// The oscillators the program knows: each one's scene schema and how to run
// it. Each oscillator registers itself in src/api/bindings/<name>_binding.cpp.
#pragma once

#include <span>
#include <string_view>

#include "io/run_output.hpp"
#include "io/scene.hpp"

namespace impactlab {

// analysis/section.hpp, analysis/periodic.hpp
struct SectionRequest;
struct SectionResult;
struct PeriodicRequest;
struct PeriodicResult;

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
};

std::span<const OscillatorEntry> oscillators();

// The entry for an oscillator name; BadInput (key `oscillator`) if unknown.
const OscillatorEntry& oscillator_entry(std::string_view name);

}  // namespace impactlab
