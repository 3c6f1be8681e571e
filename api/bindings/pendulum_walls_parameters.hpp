// The pendulum's physical parameters read from a scene, shared by every
// model of the pendulum (pendulum_walls_binding.cpp, rigid_pendulum_binding.cpp).
#pragma once

#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace impactlab {

// m, l, b, d, g, V0, ω, e_n, e_t, μ and accumulation_tol of a validated
// pendulum_walls scene; BadInput for what needs several keys at once (b < l)
// and for integrator.method = exact (the pendulum has no closed-form flow).
PendulumWallsParameters pendulum_walls_parameters(const Scene& scene);

}  // namespace impactlab
