#include "api/oscillator_registry.hpp"

#include <array>
#include <string>

#include "io/bad_input.hpp"

namespace impactlab {

// defined in src/api/bindings/<name>_binding.cpp
const OscillatorEntry& pendulum_walls_entry();
const OscillatorEntry& linear_impact_entry();
const OscillatorEntry& bouncing_ball_entry();

std::span<const OscillatorEntry> oscillators() {
  static const std::array<OscillatorEntry, 3> entries = {
      pendulum_walls_entry(), linear_impact_entry(), bouncing_ball_entry()};
  return entries;
}

const OscillatorEntry& oscillator_entry(std::string_view name) {
  std::string known;
  for (const auto& entry : oscillators()) {
    if (entry.schema->oscillator == name) return entry;
    known += (known.empty() ? "" : ", ") + std::string(entry.schema->oscillator);
  }
  throw BadInput("oscillator", std::string(name), "unknown oscillator (known: " + known + ")");
}

}  // namespace impactlab
