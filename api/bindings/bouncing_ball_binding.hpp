// The ball bouncing on a vibrating table (oscillators/bouncing_ball/): every
// analysis, and the closed-form flow (integrator.method = exact).
// api/scene_system.hpp says what a binding is.
#pragma once

#include <string_view>

#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>

namespace impactlab {

const SceneSchema& bouncing_ball_schema();

struct BouncingBallBinding {
  using System = BouncingBall;
  using State = BouncingBall::State;
  using Mode = BouncingBall::Mode;

  static const SceneSchema& schema() { return bouncing_ball_schema(); }
  static bool matches(const Scene& scene) { return scene.oscillator == "bouncing_ball"; }
  static System make_system(const Scene& scene);
  static State initial_state(const Scene& scene, const System& system);
  static Mode flight_mode(const System&) { return Mode::free; }
  static double forcing_frequency(const System& system) { return system.parameters().omega; }
  // a continued state below the table at t0, or stuck on it, starts on the
  // table, moving with it
  static void admit(const System& system, const Scene& scene, State& x, Mode& mode) {
    const double t0 = scene.number("t0");
    if (x[0] < system.table_position(t0) || mode == Mode::stuck) {
      x = {system.table_position(t0), system.table_velocity(t0)};
      mode = Mode::free;
    }
  }
  static std::string_view mode_name(const System&, Mode mode) {
    return mode == Mode::free ? "free" : "stuck";
  }
};

}  // namespace impactlab
