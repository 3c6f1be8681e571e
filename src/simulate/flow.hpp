// One event-loop run of a system with the stepper a scene names, chosen at
// run time: each stepper compiled once per system, and the loop once per
// system (it drives the steppers through simulate/stepper_view.hpp).
//
// A Flow<System> owns one stepper of the named method (as a with_stepper
// scope does) and runs simulate() with it; it may run several stretches in a
// row (simulate() initializes the stepper at each start). The loop and the
// stepper are bound together in simulate/flow_engines.hpp, and compiled in
// the translation units that instantiate them (IMPACTLAB_FLOW_ENGINES): code
// that only runs flows includes this light header and never instantiates
// the loop itself, so an analysis compiles once per system, not once per
// system and stepper. The cost is one indirect call per run, one per step to
// ask the observer for its next time, and the stepper view's few per step.
#pragma once

#include <cmath>
#include <memory>
#include <string_view>
#include <type_traits>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/stepper_settings.hpp>
#include <impactlab/simulate/simulator.hpp>

namespace impactlab {

// A non-owning view of an observer (simulate/simulator.hpp: next_time(),
// observe(t, x, mode)) of any type; the default observes nothing.
template <class State, class Mode>
class ObserverRef {
 public:
  ObserverRef() = default;
  template <class Observer>
    requires(!std::is_same_v<std::remove_cvref_t<Observer>, ObserverRef>)
  ObserverRef(Observer& observer)  // NOLINT(google-explicit-constructor): a view
      : self_(&observer),
        next_time_([](void* self) { return static_cast<Observer*>(self)->next_time(); }),
        observe_([](void* self, double t, const State& x, Mode mode) {
          static_cast<Observer*>(self)->observe(t, x, mode);
        }) {}

  [[nodiscard]] double next_time() const { return self_ ? next_time_(self_) : INFINITY; }
  void observe(double t, const State& x, Mode mode) {
    if (self_) observe_(self_, t, x, mode);
  }

 private:
  void* self_ = nullptr;
  double (*next_time_)(void*) = nullptr;
  void (*observe_)(void*, double, const State&, Mode) = nullptr;
};

// The event loop bound to one stepper for System.
template <HybridSystem System>
class FlowEngine {
 public:
  using State = typename System::State;
  using Mode = typename System::Mode;
  virtual ~FlowEngine() = default;
  virtual RunResult<State, Mode> run(const System& system, const State& x, Mode mode, double t0,
                                     double t_end, const LoopOptions& options, EventLog& log,
                                     ObserverRef<State, Mode> observer) = 0;
};

// A fresh engine with a stepper of the named integrator.method for System;
// std::invalid_argument for an unknown method, `taylor` for a system without
// a series right-hand side, `exact` for one without a closed-form flow.
// Declared here, defined in simulate/flow_engines.hpp and instantiated once
// per system type where IMPACTLAB_FLOW_ENGINES names it.
template <HybridSystem System>
std::unique_ptr<FlowEngine<System>> make_flow_engine(std::string_view method,
                                                     const StepperSettings& settings);

template <HybridSystem System>
class Flow {
 public:
  using State = typename System::State;
  using Mode = typename System::Mode;

  Flow(std::string_view method, const StepperSettings& settings)
      : engine_(make_flow_engine<System>(method, settings)) {}

  // simulate(system, stepper, x, mode, t0, t_end, options, log, observer)
  // with this flow's stepper
  template <class Observer = NoObserver>
  RunResult<State, Mode> run(const System& system, const State& x, Mode mode, double t0,
                             double t_end, const LoopOptions& options, EventLog& log,
                             Observer&& observer = Observer{}) {
    return engine_->run(system, x, mode, t0, t_end, options, log,
                        ObserverRef<State, Mode>(observer));
  }

 private:
  std::unique_ptr<FlowEngine<System>> engine_;
};

// simulate() over a flow: generic code that runs "a stepper" runs a flow the
// same way (analysis/floquet.hpp's flows with the caller's stepper).
template <HybridSystem System, class Observer = NoObserver>
RunResult<typename System::State, typename System::Mode> simulate(
    const System& system, Flow<System>& flow, const typename System::State& x,
    typename System::Mode mode, double t0, double t_end, const LoopOptions& options,
    EventLog& log, Observer&& observer = Observer{}) {
  return flow.run(system, x, mode, t0, t_end, options, log, observer);
}

// Calls body(flow) with a fresh Flow<System> of the named method and returns
// what it returns: with_stepper (integrate/stepper_dispatch.hpp) with the
// body compiled once, not once per stepper.
template <HybridSystem System, class Body>
decltype(auto) with_flow(std::string_view method, const StepperSettings& settings, Body&& body) {
  Flow<System> flow(method, settings);
  return body(flow);
}

// One run with a stepper of its own (a with_stepper scope around one
// simulate() call).
template <HybridSystem System, class Observer = NoObserver>
RunResult<typename System::State, typename System::Mode> run_flow(
    const System& system, std::string_view method, const StepperSettings& settings,
    const typename System::State& x, typename System::Mode mode, double t0, double t_end,
    const LoopOptions& options, EventLog& log, Observer&& observer = Observer{}) {
  Flow<System> flow(method, settings);
  return flow.run(system, x, mode, t0, t_end, options, log, observer);
}

}  // namespace impactlab
