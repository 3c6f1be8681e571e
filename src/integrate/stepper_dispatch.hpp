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

// The stepper type of each integrator.method for System, named as the method
// is: the one table from integrator.method to stepper. with_stepper_type reads
// it, and so do the translation units that compile one stepper's engines
// (simulate/flow_engines.hpp). `taylor` needs HasSeriesRhs, `exact`
// HasExactFlow.
namespace stepper_of {
template <HybridSystem System>
using dopri5 = OdeintDopri5<typename System::State>;
template <HybridSystem System>
using rkf78 = OdeintFehlberg78<typename System::State>;
template <HybridSystem System>
using bulirsch_stoer = OdeintBulirschStoer<typename System::State>;
template <HybridSystem System>
using rk8pd = GslRk8pd<typename System::State>;
template <HasSeriesRhs System>
using taylor = TaylorStepper<System>;
template <HasExactFlow System>
using exact = ExactFlowStepper<System>;
}  // namespace stepper_of

// Calls `body.template operator()<Stepper>()` with the stepper type of the
// named method for `System`, and returns what it returns. `exact` needs
// HasExactFlow, `taylor` HasSeriesRhs; std::invalid_argument otherwise, and
// for an unknown name.
template <HybridSystem System, class Body>
decltype(auto) with_stepper_type(std::string_view method, Body&& body) {
  if (method == "dopri5") return body.template operator()<stepper_of::dopri5<System>>();
  if (method == "rkf78") return body.template operator()<stepper_of::rkf78<System>>();
  if (method == "bulirsch_stoer")
    return body.template operator()<stepper_of::bulirsch_stoer<System>>();
  if (method == "rk8pd") return body.template operator()<stepper_of::rk8pd<System>>();
  if (method == "taylor") {
    if constexpr (HasSeriesRhs<System>)
      return body.template operator()<stepper_of::taylor<System>>();
    else
      throw std::invalid_argument(
          "integrator.method = taylor: this system's right-hand side is not written over a "
          "number type (no Taylor series for it)");
  }
  if (method == "exact") {
    if constexpr (HasExactFlow<System>)
      return body.template operator()<stepper_of::exact<System>>();
    else
      throw std::invalid_argument("integrator.method = exact: this oscillator has no closed-form flow");
  }
  throw std::invalid_argument("integrator.method = " + std::string(method) + ": unknown method");
}

// Calls `body(stepper)` with a freshly constructed stepper of the named method
// for `System`, and returns what it returns.
template <HybridSystem System, class Body>
decltype(auto) with_stepper(std::string_view method, const StepperSettings& settings, Body&& body) {
  return with_stepper_type<System>(method, [&]<class Stepper>() -> decltype(auto) {
    Stepper stepper(settings);
    return body(stepper);
  });
}

}  // namespace impactlab
