// The definition of make_flow_engine (simulate/flow.hpp): the event loop bound
// to each stepper of integrate/. Included only by the translation units that
// instantiate engines, through IMPACTLAB_FLOW_ENGINES(System): one such line
// per system type the program runs.
#pragma once

#include <memory>
#include <string_view>

#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/simulate/dense_output_stepper.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>

namespace impactlab {

namespace detail {

template <HybridSystem System, class Stepper>
class SteppedFlowEngine final : public FlowEngine<System> {
  static_assert(DenseOutputStepper<Stepper, System>,
                "every stepper the event loop drives is a dense-output stepper");

 public:
  using State = typename System::State;
  using Mode = typename System::Mode;

  explicit SteppedFlowEngine(const StepperSettings& settings) : stepper_(settings) {}

  RunResult<State, Mode> run(const System& system, const State& x, Mode mode, double t0,
                             double t_end, const LoopOptions& options, EventLog& log,
                             ObserverRef<State, Mode> observer) override {
    return simulate(system, stepper_, x, mode, t0, t_end, options, log, observer);
  }

 private:
  Stepper stepper_;
};

}  // namespace detail

template <HybridSystem System>
std::unique_ptr<FlowEngine<System>> make_flow_engine(std::string_view method,
                                                     const StepperSettings& settings) {
  return with_stepper_type<System>(
      method, [&]<class Stepper>() -> std::unique_ptr<FlowEngine<System>> {
        return std::make_unique<detail::SteppedFlowEngine<System, Stepper>>(settings);
      });
}

}  // namespace impactlab

// The engines of one system type, compiled in this translation unit (at
// namespace scope, once per type in the whole program).
#define IMPACTLAB_FLOW_ENGINES(...)                                                      \
  template std::unique_ptr<::impactlab::FlowEngine<__VA_ARGS__>>                         \
  impactlab::make_flow_engine<__VA_ARGS__>(std::string_view, const ::impactlab::StepperSettings&)
