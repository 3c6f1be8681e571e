#include <impactlab/api/oscillator_registry.hpp>

#include <map>
#include <mutex>
#include <string>

#include <impactlab/api/builtin_bindings.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

// one entry per schema: the bindings of one oscillator's models share it
template <class... Bindings>
std::vector<OscillatorEntry> builtin_entries(BindingList<Bindings...>) {
  std::vector<OscillatorEntry> entries;
  auto add = [&entries]<class Binding>() {
    if constexpr (requires { Binding::schema(); }) {
      const SceneSchema* schema = &Binding::schema();
      for (const OscillatorEntry& entry : entries)
        if (entry.schema == schema) return;
      entries.push_back({schema});
    }
  };
  (add.template operator()<Bindings>(), ...);
  return entries;
}

}  // namespace

std::span<const OscillatorEntry> oscillators() {
  static const std::vector<OscillatorEntry> entries = builtin_entries(BuiltinBindings{});
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
