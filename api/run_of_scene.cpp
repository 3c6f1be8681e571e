#include <impactlab/api/system_jobs.hpp>

#include <numbers>

#include <impactlab/api/event_tap.hpp>
#include <impactlab/api/run_system.hpp>
#include <impactlab/api/visit_scene.hpp>

namespace impactlab {

RunOutput run_of_scene(const Scene& scene, const RunRequest& request) {
  return visit_scene(scene, [&]<class Binding>(const SceneSystem<Binding>& bound) {
    const auto& system = bound.system();
    const auto x0 = bound.initial_state();
    const double period = 2.0 * std::numbers::pi / bound.forcing_frequency();
    auto mode_name = [&bound](auto mode) { return bound.mode_name(mode); };
    RunOutput output;
    if constexpr (requires { Binding::run_tally(system, scene); }) {
      // the derived quantities, tallied as the events pass (kept or streamed)
      auto tally = Binding::run_tally(system, scene);
      EventTap tap([&tally](const EventRecord& event) { tally.on_event(event); },
                   request.event_sink);
      RunRequest tallied = request;
      tallied.event_sink = &tap;
      output = run_system(system, x0, bound.flight_mode(), scene, tallied, period, mode_name);
      tally.add_to(output);
    } else {
      output = run_system(system, x0, bound.flight_mode(), scene, request, period, mode_name);
    }
    if (output.termination != Termination::completed) output.stop_advice = bound.stop_advice(output);
    output.event_columns = bound.event_columns();
    return output;
  });
}

EventExtender event_extender_of_scene(const Scene& scene) {
  return visit_scene(scene, [](const auto& bound) { return bound.event_extender(); });
}

EventColumns event_columns_of_scene(const Scene& scene) {
  return visit_scene(scene, [](const auto& bound) { return bound.event_columns(); });
}

}  // namespace impactlab
