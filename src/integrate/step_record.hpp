// The last accepted step of a stepper without a continuous extension of its
// own (rkf78, rk8pd): both end states and end derivatives, their cubic
// Hermite interpolant for the event scan, and the last state re-taken inside
// the step (the event refinement asks for its final time twice).
#pragma once

#include <cmath>

#include <impactlab/integrate/cubic_hermite.hpp>

namespace impactlab {

template <class State>
class StepRecord {
 public:
  State x{}, x_old{};        // states at the step's end and start
  State dxdt{}, dxdt_old{};  // derivatives there
  double t = 0.0, t_old = 0.0;  // s

  // the current end becomes the start of the next step
  void begin_step() {
    x_old = x;
    dxdt_old = dxdt;
    t_old = t;
    t_retaken_ = NAN;
  }

  // the interpolant, for the event scan only (3rd order inside the step)
  void interpolate(double at, State& out) const {
    cubic_hermite(t_old, x_old, dxdt_old, t, x, dxdt, at, out);
  }

  // The state at `at` inside the step: the end state, the last re-taken one,
  // or retake(out), which takes the step from (t_old, x_old) to `at`.
  template <class Retake>
  void state_at(double at, State& out, Retake&& retake) {
    if (at == t) {
      out = x;
    } else if (at == t_retaken_) {
      out = x_retaken_;
    } else {
      retake(out);
      t_retaken_ = at;
      x_retaken_ = out;
    }
  }

 private:
  double t_retaken_ = NAN;  // time of the last re-taken state (s)
  State x_retaken_{};
};

}  // namespace impactlab
