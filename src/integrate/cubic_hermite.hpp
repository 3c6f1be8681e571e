// The cubic Hermite interpolant of a step from its end states and end
// derivatives: 3rd-order accurate inside the step, exact at its ends. Used by
// the steppers without a continuous extension of their own, for the event
// scan only (every refinement uses the stepper's own step).
#pragma once

#include <cstddef>

namespace impactlab {

// x(t) for t in [t0, t1], from x0 = x(t0), f0 = x'(t0), x1 = x(t1), f1 = x'(t1).
template <class State>
void cubic_hermite(double t0, const State& x0, const State& f0, double t1, const State& x1,
                   const State& f1, double t, State& x) {
  const double h = t1 - t0;
  const double s = (t - t0) / h;
  const double h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s);
  const double h10 = s * (1.0 - s) * (1.0 - s);
  const double h01 = s * s * (3.0 - 2.0 * s);
  const double h11 = s * s * (s - 1.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = h00 * x0[i] + h10 * h * f0[i] + h01 * x1[i] + h11 * h * f1[i];
}

}  // namespace impactlab
