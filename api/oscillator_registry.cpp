#include <impactlab/api/oscillator_registry.hpp>

#include <array>
#include <map>
#include <mutex>
#include <string>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

// defined in api/bindings/<name>_binding.cpp
const OscillatorEntry& pendulum_walls_entry();
const OscillatorEntry& linear_impact_entry();
const OscillatorEntry& bouncing_ball_entry();

std::span<const OscillatorEntry> oscillators() {
  static const std::array<OscillatorEntry, 3> entries = {
      pendulum_walls_entry(), linear_impact_entry(), bouncing_ball_entry()};
  return entries;
}

namespace {

// The oscillators registered at run time, by name, with the lock that guards them.
struct RuntimeRegistry {
  std::mutex lock;
  std::map<std::string, std::unique_ptr<RuntimeOscillator>, std::less<>> entries;
};

RuntimeRegistry& runtime_registry() {
  static RuntimeRegistry registry;
  return registry;
}

}  // namespace

const RuntimeOscillator& register_runtime_oscillator(std::unique_ptr<RuntimeOscillator> oscillator) {
  RuntimeRegistry& registry = runtime_registry();
  const std::lock_guard<std::mutex> guard(registry.lock);
  auto& slot = registry.entries[oscillator->name];
  if (!slot) slot = std::move(oscillator);
  return *slot;
}

const RuntimeOscillator* runtime_oscillator(std::string_view name) {
  RuntimeRegistry& registry = runtime_registry();
  const std::lock_guard<std::mutex> guard(registry.lock);
  const auto found = registry.entries.find(name);
  return found == registry.entries.end() ? nullptr : found->second.get();
}

const OscillatorEntry& oscillator_entry(std::string_view name) {
  std::string known;
  for (const auto& entry : oscillators()) {
    if (entry.schema->oscillator == name) return entry;
    known += (known.empty() ? "" : ", ") + std::string(entry.schema->oscillator);
  }
  if (const RuntimeOscillator* runtime = runtime_oscillator(name)) return runtime->entry;
  throw BadInput("oscillator", std::string(name), "unknown oscillator (known: " + known + ")");
}

}  // namespace impactlab
