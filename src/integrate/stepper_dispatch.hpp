// Choosing a stepper by name, once per run: the name selects a template
// instantiation of the whole event loop, so nothing inside it dispatches at
// run time.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/exact_flow_stepper.hpp>
#include <impactlab/integrate/gsl_rk8pd.hpp>
#include <impactlab/integrate/odeint_bulirsch_stoer.hpp>
#include <impactlab/integrate/odeint_dopri5.hpp>
#include <impactlab/integrate/odeint_fehlberg78.hpp>
#include <impactlab/integrate/stepper_names.hpp>
#include <impactlab/integrate/stepper_settings.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>

namespace impactlab {

// Calls `body(stepper)` with a freshly constructed stepper of the named method
// for `System`, and returns what it returns. `exact` needs HasExactFlow,
// `taylor` HasSeriesRhs.
template <HybridSystem System, class Body>
decltype(auto) with_stepper(std::string_view method, const StepperSettings& settings, Body&& body) {
  using State = typename System::State;
  if (method == "dopri5") {
    OdeintDopri5<State> stepper(settings);
    return body(stepper);
  }
  if (method == "rkf78") {
    OdeintFehlberg78<State> stepper(settings);
    return body(stepper);
  }
  if (method == "bulirsch_stoer") {
    OdeintBulirschStoer<State> stepper(settings);
    return body(stepper);
  }
  if (method == "rk8pd") {
    GslRk8pd<State> stepper(settings);
    return body(stepper);
  }
  if (method == "taylor") {
    if constexpr (HasSeriesRhs<System>) {
      TaylorStepper<System> stepper(settings);
      return body(stepper);
    } else {
      throw std::invalid_argument(
          "integrator.method = taylor: this system's right-hand side is not written over a "
          "number type (no Taylor series for it)");
    }
  }
  if (method == "exact") {
    if constexpr (HasExactFlow<System>) {
      ExactFlowStepper<System> stepper(settings);
      return body(stepper);
    } else {
      throw std::invalid_argument("integrator.method = exact: this oscillator has no closed-form flow");
    }
  }
  throw std::invalid_argument("integrator.method = " + std::string(method) + ": unknown method");
}

}  // namespace impactlab
