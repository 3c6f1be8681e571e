// The linear impact oscillator (oscillators/linear_impact/): every analysis,
// and the closed-form flow (integrator.method = exact) where it exists.
// api/scene_system.hpp says what a binding is.
#pragma once

#include <string_view>

#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>

namespace impactlab {

const SceneSchema& linear_impact_schema();

struct LinearImpactBinding {
  using System = LinearImpact;
  using State = LinearImpact::State;
  using Mode = LinearImpact::Mode;

  static const SceneSchema& schema() { return linear_impact_schema(); }
  static bool matches(const Scene& scene) { return scene.oscillator == "linear_impact"; }
  // BadInput where keys clash (method = exact for an oscillator without a
  // closed form)
  static System make_system(const Scene& scene);
  static State initial_state(const Scene& scene, const System& system);
  static Mode flight_mode(const System&) { return Mode::free; }
  static double forcing_frequency(const System& system) { return system.parameters().omega; }
  // a continued state beyond a moved stop, or stuck on it, starts on it at rest
  static void admit(const System& system, const Scene&, State& x, Mode& mode) {
    const double sigma = system.parameters().sigma;
    if (x[0] > sigma || mode == Mode::stuck) {
      x = {sigma, 0.0};
      mode = Mode::free;
    }
  }
  static std::string_view mode_name(const System&, Mode mode) {
    return mode == Mode::free ? "free" : "stuck";
  }
};

}  // namespace impactlab
