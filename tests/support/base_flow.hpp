// The base system's state at t1 from (t0, x0) by the plain event loop, with
// the stepper a FlowSetup names: the reference the tangent tests difference
// (central differences of the flow against the variational equations).
#pragma once

#include <cstdint>

#include <gtest/gtest.h>

#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>

template <class System>
typename System::State flow(const System& system, const impactlab::FlowSetup& setup,
                            typename System::State x0, typename System::Mode mode, double t0,
                            double t1, std::uint64_t* impacts = nullptr) {
  impactlab::EventLog log(false);
  const auto run = impactlab::with_stepper<System>(
      setup.method, impactlab::stepper_settings(system, setup), [&](auto& stepper) {
        return impactlab::simulate(system, stepper, x0, mode, t0, t1,
                                   impactlab::loop_options(setup), log);
      });
  EXPECT_EQ(run.termination, impactlab::Termination::completed);
  if (impacts) *impacts = log.count(impactlab::EventKind::impact);
  return run.state;
}
