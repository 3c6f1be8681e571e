// The definition of make_flow_engine (simulate/flow.hpp): the event loop bound
// to each stepper of integrate/. Included only by the translation units that
// instantiate engines, through IMPACTLAB_FLOW_ENGINES(System): one such line
// per system type the program runs.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
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
  using State = typename System::State;
  if (method == "dopri5")
    return std::make_unique<detail::SteppedFlowEngine<System, OdeintDopri5<State>>>(settings);
  if (method == "rkf78")
    return std::make_unique<detail::SteppedFlowEngine<System, OdeintFehlberg78<State>>>(settings);
  if (method == "bulirsch_stoer")
    return std::make_unique<detail::SteppedFlowEngine<System, OdeintBulirschStoer<State>>>(
        settings);
  if (method == "rk8pd")
    return std::make_unique<detail::SteppedFlowEngine<System, GslRk8pd<State>>>(settings);
  if (method == "taylor") {
    if constexpr (HasSeriesRhs<System>)
      return std::make_unique<detail::SteppedFlowEngine<System, TaylorStepper<System>>>(settings);
    else
      throw std::invalid_argument(
          "integrator.method = taylor: this system's right-hand side is not written over a "
          "number type (no Taylor series for it)");
  }
  if (method == "exact") {
    if constexpr (HasExactFlow<System>)
      return std::make_unique<detail::SteppedFlowEngine<System, ExactFlowStepper<System>>>(
          settings);
    else
      throw std::invalid_argument("integrator.method = exact: this oscillator has no closed-form flow");
  }
  throw std::invalid_argument("integrator.method = " + std::string(method) + ": unknown method");
}

}  // namespace impactlab

// The engines of one system type, compiled in this translation unit (at
// namespace scope, once per type in the whole program).
#define IMPACTLAB_FLOW_ENGINES(...)                                                      \
  template std::unique_ptr<::impactlab::FlowEngine<__VA_ARGS__>>                         \
  impactlab::make_flow_engine<__VA_ARGS__>(std::string_view, const ::impactlab::StepperSettings&)
