#include "analysis/flow_setup.hpp"

#include "io/scene.hpp"

namespace impactlab {

FlowSetup flow_setup(const Scene& scene) {
  return {scene.text("integrator.method"), scene.number("integrator.rtol"),
          scene.number("integrator.atol")};
}

}  // namespace impactlab
