// One accepted step of an Odeint controlled stepper that never ends past a
// time limit: the trial step is clipped to the limit, and a step size
// suggested after a clipped step does not shrink the one carried over.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>

#include <boost/numeric/odeint.hpp>

namespace impactlab {

// try_step(t, dt) makes one attempt from t with step dt, as Odeint's
// controlled try_step does (t advanced and dt updated on success, dt reduced
// on failure). `dt` is the carried step size (s); returns the step's end time.
template <class TryStep>
double step_to_limit(double t_start, double t_limit, double max_step, double& dt,
                     const char* method, TryStep&& try_step) {
  constexpr int max_attempts = 500;
  for (int attempt = 0; attempt <= max_attempts; ++attempt) {
    const double room = t_limit - t_start;
    const bool clipped = dt >= room;
    double trial = clipped ? room : dt;
    double t = t_start;
    if (try_step(t, trial) == boost::numeric::odeint::success) {
      if (!clipped || trial > dt) dt = std::min(trial, max_step);
      return clipped ? t_limit : t;
    }
    dt = trial;
  }
  throw std::runtime_error(std::string(method) + ": step size underflow");
}

}  // namespace impactlab
