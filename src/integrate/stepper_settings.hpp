// Settings shared by every dense-output stepper, and the right-hand side of
// one mode bound into the `sys(x, dxdt, t)` shape that Boost.Odeint expects.
#pragma once

#include <cstdint>
#include <string>

#include <impactlab/integrate/series_lane.hpp>

namespace impactlab {

struct StepperSettings {
  double rtol = 1e-10;      // relative error per step (dimensionless)
  double atol = 1e-12;      // absolute error per step (state units)
  double max_step = 0.1;    // largest step (s); set from the system
  double initial_step = 1e-3;  // first trial step (s)
  // the batch lane a Taylor stepper gets its series from
  // (integrate/series_lane.hpp); none: it computes them itself. The other
  // steppers ignore it.
  SeriesLane* series_lane = nullptr;
};

// The vector field of one mode of a hybrid system, with an evaluation
// counter. A plain struct called through a template parameter: the compiler
// sees `system->rhs` and inlines it; no virtual call per evaluation.
template <class System>
struct ModeRhs {
  using State = typename System::State;
  const System* system;
  typename System::Mode mode;
  std::uint64_t* evaluations;

  void operator()(const State& x, State& dxdt, double t) const {
    ++*evaluations;
    system->rhs(mode, x, dxdt, t);
  }
};

}  // namespace impactlab
