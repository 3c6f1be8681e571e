// A plain run of the pendulum scene from a state on the stroboscopic section
// ωt ≡ phase, at (V0, ω): the check of a located point or curve point of the
// pendulum against the simulation itself.
#pragma once

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab::testing {

inline RunOutput pendulum_run_from(Scene scene, const OrbitPoint& state, double v0, double omega,
                                   double phase, double periods) {
  scene.values["V0"] = v0;
  scene.values["omega"] = omega;
  scene.values["initial.theta"] = state[0];
  scene.values["initial.theta_dot"] = state[1];
  scene.values["t0"] = phase / omega;
  RunRequest request;
  request.periods = periods;
  return simulate(scene, request);
}

}  // namespace impactlab::testing
