#include "analysis/flow_setup.hpp"

#include "io/scene.hpp"

namespace impactlab {

FlowSetup flow_setup(const Scene& scene) {
  return {scene.text("integrator.method"), scene.number("integrator.rtol"),
          scene.number("integrator.atol"),
          static_cast<std::uint64_t>(scene.number("limits.max_steps"))};
}

}  // namespace impactlab
