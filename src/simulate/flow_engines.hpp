// The definition of make_flow_engine (simulate/flow.hpp): the event loop bound
// to each stepper of integrate/. Included only by the translation units that
// instantiate engines, through IMPACTLAB_FLOW_ENGINES(System): one such line
// per system type the program runs. Where one system's engines together take
// too long to compile in one unit, each stepper's engine can be compiled in a
// unit of its own (IMPACTLAB_STEPPED_FLOW_ENGINE below).
#pragma once

#include <memory>
#include <string_view>
#include <type_traits>
#include <utility>

#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/simulate/dense_output_stepper.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/stepper_view.hpp>

namespace impactlab {

namespace detail {

// The loop on a SteppingView of the stepper, so that one loop serves every
// stepper of the system (simulate/stepper_view.hpp).
template <HybridSystem System, class Stepper>
class SteppedFlowEngine final : public FlowEngine<System> {
  static_assert(DenseOutputStepper<Stepper, System>,
                "every stepper the event loop drives is a dense-output stepper");
  static_assert(DenseOutputStepper<SteppingView<System>, System>);

 public:
  using State = typename System::State;
  using Mode = typename System::Mode;

  explicit SteppedFlowEngine(const StepperSettings& settings) : stepper_(settings) {}

  RunResult<State, Mode> run(const System& system, const State& x, Mode mode, double t0,
                             double t_end, const LoopOptions& options, EventLog& log,
                             ObserverRef<State, Mode> observer) override {
    SteppingView<System>& stepper = stepper_;
    return simulate(system, stepper, x, mode, t0, t_end, options, log, observer);
  }

 private:
  SteppingViewOf<System, Stepper> stepper_;
};

// The flows of System run by the engine of Runner, a view of it made for
// each run (Runner(system)) with the same states, modes and events.
template <HybridSystem System, HybridSystem Runner>
class ForwardingFlowEngine final : public FlowEngine<System> {
  static_assert(std::is_same_v<typename Runner::State, typename System::State> &&
                std::is_same_v<typename Runner::Mode, typename System::Mode>);

 public:
  using State = typename System::State;
  using Mode = typename System::Mode;

  explicit ForwardingFlowEngine(std::unique_ptr<FlowEngine<Runner>> runner)
      : runner_(std::move(runner)) {}

  RunResult<State, Mode> run(const System& system, const State& x, Mode mode, double t0,
                             double t_end, const LoopOptions& options, EventLog& log,
                             ObserverRef<State, Mode> observer) override {
    return runner_->run(Runner(system), x, mode, t0, t_end, options, log, observer);
  }

 private:
  std::unique_ptr<FlowEngine<Runner>> runner_;
};

}  // namespace detail

// The system type whose engines run System's flows: System itself, or a view
// of it with the same flows, number for number, whose engines the program
// compiles anyway, so that System's own are not compiled again. A
// specialization names the view before System's engines are instantiated
// (analysis/analysis_flows.hpp: a system runs as its DecoratedSystem with
// nothing switched on).
template <HybridSystem System>
struct FlowRunner {
  using type = System;
};

// The event loop bound to one stepper of with_stepper_type's table for
// System: one engine, compiled where a macro below names the pair.
template <HybridSystem System, class Stepper>
std::unique_ptr<FlowEngine<System>> make_stepped_flow_engine(const StepperSettings& settings) {
  return std::make_unique<detail::SteppedFlowEngine<System, Stepper>>(settings);
}

// The dispatch: the stepper of the named method, its engine made by
// make_stepped_flow_engine.
template <HybridSystem System>
std::unique_ptr<FlowEngine<System>> make_flow_engine(std::string_view method,
                                                     const StepperSettings& settings) {
  using Runner = typename FlowRunner<System>::type;
  if constexpr (!std::is_same_v<Runner, System>)
    return std::make_unique<detail::ForwardingFlowEngine<System, Runner>>(
        make_flow_engine<Runner>(method, settings));
  else
    return with_stepper_type<System>(
        method, [&]<class Stepper>() -> std::unique_ptr<FlowEngine<System>> {
          return make_stepped_flow_engine<System, Stepper>(settings);
        });
}

}  // namespace impactlab

// The engines of one system type, at namespace scope, once per type in the
// whole program: the dispatch, and the engine of each of the system's
// steppers, compiled in this translation unit but for those that an
// IMPACTLAB_EXTERN_STEPPED_FLOW_ENGINE line above it declares compiled in
// another.
#define IMPACTLAB_FLOW_ENGINES(...)                                                      \
  template std::unique_ptr<::impactlab::FlowEngine<__VA_ARGS__>>                         \
  impactlab::make_flow_engine<__VA_ARGS__>(std::string_view, const ::impactlab::StepperSettings&)

// The engine of one stepper for one system type, METHOD an integrator.method
// (stepper_of in integrate/stepper_dispatch.hpp), compiled in this
// translation unit: a system whose engines take too long to compile in one
// unit spreads them over several, once per pair in the whole program.
#define IMPACTLAB_STEPPED_FLOW_ENGINE(METHOD, ...)                                  \
  template std::unique_ptr<::impactlab::FlowEngine<__VA_ARGS__>>                    \
  impactlab::make_stepped_flow_engine<__VA_ARGS__,                                  \
                                      ::impactlab::stepper_of::METHOD<__VA_ARGS__>>( \
      const ::impactlab::StepperSettings&)

// The same engine declared compiled in another translation unit, so that
// IMPACTLAB_FLOW_ENGINES below it calls that one and does not compile it again.
#define IMPACTLAB_EXTERN_STEPPED_FLOW_ENGINE(METHOD, ...)                           \
  extern template std::unique_ptr<::impactlab::FlowEngine<__VA_ARGS__>>             \
  impactlab::make_stepped_flow_engine<__VA_ARGS__,                                  \
                                      ::impactlab::stepper_of::METHOD<__VA_ARGS__>>( \
      const ::impactlab::StepperSettings&)
