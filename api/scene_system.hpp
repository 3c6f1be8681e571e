// What every analysis gets of a scene's oscillator: the system the scene
// describes, built once, and the few facts about it that no analysis can
// work out alone (its initial state, its flight mode, its forcing frequency,
// where a continued state must be moved when walls move).
//
// An oscillator tells them through a binding (api/bindings/<name>_binding.hpp),
// a struct of static functions:
//
//   using System = ...;                                   a HybridSystem
//   static bool matches(const Scene&);                    this binding runs this scene
//   static System make_system(const Scene&);              BadInput for keys that clash
//   static State initial_state(const Scene&, const System&);   validated
//   static Mode flight_mode(const System&);               where runs and orbits start
//   static double forcing_frequency(const System&);       rad/s: 2π/ω is a period
//   static void admit(const System&, const Scene&, State&, Mode&);
//                        a continued state moved into the admissible set
//   static std::string_view mode_name(const System&, Mode);   trajectory.csv's mode
//
// and, where it has them:
//
//   static std::vector<SceneBoundary> boundaries();       continuation's parameter boundaries
//   static std::string without_linearisation(const System&);
//                        why Floquet, Lyapunov and continuation cannot run (empty: they can)
//   static Tally run_tally(const System&, const Scene&);  meta.json's derived quantities,
//                        Tally: on_event(const EventRecord&), add_to(RunOutput&)
//   static EventExtender event_extender(const System&);   what its events add to the
//                        core's record (io/event_extension.hpp): events.csv's own columns
//   static EventColumns event_columns(const System&);     events.csv's columns beyond the
//                        core's that its events fill (io/event_columns.hpp; none without)
//   static std::string stop_advice(const System&, const RunOutput&);
//                        what to do about a run that stopped early (empty: nothing to add)
//
// The analyses reach a binding through visit_scene (api/visit_scene.hpp) and
// never name an oscillator; a binding never names an analysis.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <impactlab/analysis/scene_boundary.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/io/event_columns.hpp>
#include <impactlab/io/event_extension.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

template <class Binding>
class SceneSystem {
 public:
  using System = typename Binding::System;
  using State = typename System::State;
  using Mode = typename System::Mode;

  explicit SceneSystem(const Scene& scene) : scene_(scene), system_(Binding::make_system(scene)) {}

  [[nodiscard]] const Scene& scene() const { return scene_; }
  [[nodiscard]] const System& system() const { return system_; }
  [[nodiscard]] State initial_state() const { return Binding::initial_state(scene_, system_); }
  // the initial state another scene of the same system gives (its initial.* keys)
  [[nodiscard]] State initial_state_of(const Scene& other) const {
    return Binding::initial_state(other, system_);
  }
  [[nodiscard]] Mode flight_mode() const { return Binding::flight_mode(system_); }
  [[nodiscard]] double forcing_frequency() const { return Binding::forcing_frequency(system_); }
  [[nodiscard]] std::string_view mode_name(Mode mode) const {
    return Binding::mode_name(system_, mode);
  }

  // admit(State&, Mode&): moves a continued state into the admissible set
  [[nodiscard]] auto admissible() const {
    return [this](State& x, Mode& mode) { Binding::admit(system_, scene_, x, mode); };
  }

  // what the system's events add to the core's record; empty where nothing
  [[nodiscard]] EventExtender event_extender() const {
    if constexpr (requires { Binding::event_extender(system_); })
      return Binding::event_extender(system_);
    else
      return {};
  }

  // events.csv's columns beyond the core's that the system's events fill
  [[nodiscard]] EventColumns event_columns() const {
    if constexpr (requires { Binding::event_columns(system_); })
      return Binding::event_columns(system_);
    else
      return {};
  }

  // the system another scene (the same oscillator, other keys) describes
  [[nodiscard]] static System system_at(const Scene& scene) { return Binding::make_system(scene); }

  [[nodiscard]] static std::vector<SceneBoundary> boundaries() {
    if constexpr (requires { Binding::boundaries(); })
      return Binding::boundaries();
    else
      return {};
  }

  // what to do about a run of this system that stopped early; empty where
  // the binding has nothing to add
  [[nodiscard]] std::string stop_advice(const RunOutput& output) const {
    if constexpr (requires { Binding::stop_advice(system_, output); })
      return Binding::stop_advice(system_, output);
    else
      return {};
  }

  // why the tangent dynamics (Floquet, Lyapunov, continuation) are not
  // available for this system; empty where they are
  [[nodiscard]] std::string without_linearisation() const {
    if constexpr (!HasJacobian<System>)
      return "this oscillator/model has no Jacobians";
    else if constexpr (requires { Binding::without_linearisation(system_); })
      return Binding::without_linearisation(system_);
    else
      return {};
  }

 private:
  const Scene& scene_;
  System system_;
};

}  // namespace impactlab
