#include <impactlab/analysis/flow_setup.hpp>

#include <impactlab/analysis/section.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

FlowSetup flow_setup(const Scene& scene) {
  return {scene.text("integrator.method"), scene.number("integrator.rtol"),
          scene.number("integrator.atol"),
          static_cast<std::uint64_t>(scene.number("limits.max_steps"))};
}

FlowSetup with_integrator(FlowSetup setup, const IntegratorSetting& integrator) {
  setup.method = integrator.method;
  setup.rtol = integrator.rtol;
  setup.atol = integrator.atol;
  return setup;
}

IntegratorSetting scene_integrator(const Scene& scene) {
  return {scene.text("integrator.method"), scene.number("integrator.rtol"),
          scene.number("integrator.atol")};
}

}  // namespace impactlab
