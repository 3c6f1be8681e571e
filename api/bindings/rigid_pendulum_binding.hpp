// Runs a pendulum_walls scene with model = "rigid" (rigid_pendulum_walls.hpp).
#pragma once

#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// Reads the pendulum's keys and, for the rigid model, `radius` and `spin`;
// throws BadInput where they do not fit together (radius >= b, spin = free
// with radius = 0, the bob starting inside a wall).
RunOutput run_rigid_pendulum(const Scene& scene, const RunRequest& request);

}  // namespace impactlab
