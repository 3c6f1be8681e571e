// Every oscillator binding the program is built with, in the order the scene
// loader lists their oscillators. Adding an oscillator: its model under
// oscillators/<name>/ with its scene file, its binding under api/bindings/
// (and the line instantiating its flows), and one entry here
// (docs/extending.md).
#pragma once

#include <impactlab/api/bindings/bouncing_ball_binding.hpp>
#include <impactlab/api/bindings/linear_impact_binding.hpp>
#include <impactlab/api/bindings/model_file_binding.hpp>
#include <impactlab/api/bindings/pendulum_walls_binding.hpp>

namespace impactlab {

template <class... Bindings>
struct BindingList {};

using BuiltinBindings =
    BindingList<PendulumBinding<PendulumModel::newton>, PendulumBinding<PendulumModel::paper>,
                RigidPendulumBinding<RigidSpin::locked>,
                RigidPendulumBinding<RigidSpin::free>, LinearImpactBinding, BouncingBallBinding,
                ModelFileBinding<2>, ModelFileBinding<4>>;

}  // namespace impactlab
