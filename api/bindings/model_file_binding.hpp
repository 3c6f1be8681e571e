// Oscillators defined in a scene file's [model] section
// (oscillators/model_file/): every analysis, for 2 or up to 4 states (the
// state padded to 4). register_model_scene (api/oscillator_registry.hpp) loads
// and compiles the model; these bindings run it. api/scene_system.hpp says
// what a binding is.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>

namespace impactlab {

template <std::size_t N>
struct ModelFileBinding {
  using System = ModelSystem<N>;
  using State = typename System::State;

  // the scene names a loaded model with this binding's state count
  static bool matches(const Scene& scene);
  static System make_system(const Scene& scene);
  // BadInput where the initial values break the model's own checks
  static State initial_state(const Scene& scene, const System& system);
  static ModelMode flight_mode(const System&) { return System::free_mode; }
  static double forcing_frequency(const System& system) { return system.forcing_frequency(); }
  // a continued state keeps its values and starts in free flight
  static void admit(const System&, const Scene&, State&, ModelMode& mode) {
    mode = System::free_mode;
  }
  static std::string_view mode_name(const System& system, ModelMode mode) {
    return system.mode_name(mode);
  }
  // a model of more than 2 states with a sticking wall has no linearisation
  // of its contact phases
  static std::string without_linearisation(const System& system);
  // impacts that accumulate on a wall without a sticking table stop the run
  // (no_progress): say which wall, and what to add
  static std::string stop_advice(const System& system, const RunOutput& output);
};

extern template struct ModelFileBinding<2>;
extern template struct ModelFileBinding<4>;

}  // namespace impactlab
