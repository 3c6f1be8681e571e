// GSL's explicit embedded Runge–Kutta Prince–Dormand 8(9) (gsl_odeiv2_step_rk8pd)
// with GSL's standard step control. GSL offers no continuous extension for
// rk8pd, so the state inside a step is the rk8pd step itself re-taken from the
// step's start to the requested time: 8th-order accurate, at 13 evaluations.
// The event locator's coarse scan of a step only has to find where to look,
// so it uses the cubic Hermite interpolant of the step's end states and
// derivatives (which GSL's evolve has already computed: no evaluation), and
// every refinement uses the re-taken step. The right-hand side is a view
// (integrate/state_rhs.hpp), so that the stepper is compiled once per state
// type, in gsl_rk8pd.cpp for the states of integrate/state_dimensions.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <impactlab/integrate/state_dimensions.hpp>
#include <impactlab/integrate/state_rhs.hpp>
#include <impactlab/integrate/step_record.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

template <class State>
class GslRk8pd {
  static constexpr std::size_t dimension = std::tuple_size_v<State>;

  struct StepDeleter {
    void operator()(gsl_odeiv2_step* p) const { gsl_odeiv2_step_free(p); }
  };
  struct ControlDeleter {
    void operator()(gsl_odeiv2_control* p) const { gsl_odeiv2_control_free(p); }
  };
  struct EvolveDeleter {
    void operator()(gsl_odeiv2_evolve* p) const { gsl_odeiv2_evolve_free(p); }
  };

  // GSL calls the right-hand side through a C function pointer with the
  // right-hand side's view as its parameter block.
  static int gsl_rhs(double t, const double y[], double dydt[], void* params);

  gsl_odeiv2_system bind(const StateRhs<State>& rhs) const {
    return gsl_odeiv2_system{&gsl_rhs, nullptr, dimension,
                             const_cast<void*>(static_cast<const void*>(&rhs))};
  }

 public:
  static constexpr const char* name = "rk8pd";
  static constexpr bool has_cheap_scan = true;  // scan_state cheaper than state_at
  static constexpr bool has_polish = false;

  explicit GslRk8pd(const StepperSettings& settings);

  void initialize(StateRhs<State> rhs, const State& x, double t, double dt);

  void do_step(StateRhs<State> rhs, double t_limit);

  // The state at t inside the last step: the rk8pd step re-taken from the
  // step's start (needs the right-hand side of the last step).
  void state_at(StateRhs<State> rhs, double t, State& x);

  void polish_state(StateRhs<State> rhs, double t, State& x) { state_at(rhs, t, x); }

  void scan_state(StateRhs<State>, double t, State& x) const { step_.interpolate(t, x); }

  [[nodiscard]] double previous_time() const { return step_.t_old; }
  [[nodiscard]] double current_time() const { return step_.t; }
  [[nodiscard]] const State& current_state() const { return step_.x; }
  [[nodiscard]] const State& previous_state() const { return step_.x_old; }
  [[nodiscard]] double suggested_step() const { return dt_; }

 private:
  StepperSettings settings_;
  std::unique_ptr<gsl_odeiv2_step, StepDeleter> step_gsl_, restep_;
  std::unique_ptr<gsl_odeiv2_control, ControlDeleter> control_;
  std::unique_ptr<gsl_odeiv2_evolve, EvolveDeleter> evolve_;
  StepRecord<State> step_;
  double dt_ = 0.0;  // carried step size (s)
};

template <class State>
int GslRk8pd<State>::gsl_rhs(double t, const double y[], double dydt[], void* params) {
  const auto& rhs = *static_cast<const StateRhs<State>*>(params);
  State x;
  std::copy_n(y, dimension, x.begin());
  State dxdt;
  rhs(x, dxdt, t);
  std::copy_n(dxdt.begin(), dimension, dydt);
  return GSL_SUCCESS;
}

template <class State>
GslRk8pd<State>::GslRk8pd(const StepperSettings& settings)
    : settings_(settings),
      step_gsl_(gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, dimension)),
      restep_(gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, dimension)),
      control_(gsl_odeiv2_control_standard_new(settings.atol, settings.rtol, 1.0, 0.0)),
      evolve_(gsl_odeiv2_evolve_alloc(dimension)) {
  if (!step_gsl_ || !restep_ || !control_ || !evolve_)
    throw std::runtime_error("rk8pd: GSL allocation failed");
}

template <class State>
void GslRk8pd<State>::initialize(StateRhs<State>, const State& x, double t, double dt) {
  step_.x = x;
  step_.t = t;
  dt_ = std::min(dt, settings_.max_step);
  gsl_odeiv2_evolve_reset(evolve_.get());
  gsl_odeiv2_step_reset(step_gsl_.get());
}

template <class State>
void GslRk8pd<State>::do_step(StateRhs<State> rhs, double t_limit) {
  step_.begin_step();
  gsl_odeiv2_system system = bind(rhs);
  const double t_stop = std::min(t_limit, step_.t_old + settings_.max_step);
  double t = step_.t_old;
  const int status = gsl_odeiv2_evolve_apply(evolve_.get(), control_.get(), step_gsl_.get(),
                                             &system, &t, t_stop, &dt_, step_.x.data());
  if (status != GSL_SUCCESS)
    throw std::runtime_error("rk8pd: gsl_odeiv2_evolve_apply failed: " +
                             std::string(gsl_strerror(status)));
  step_.t = t;
  dt_ = std::min(dt_, settings_.max_step);
  // the derivatives at both ends of the accepted step, as evolve computed them
  std::copy_n(evolve_->dydt_in, dimension, step_.dxdt_old.begin());
  std::copy_n(evolve_->dydt_out, dimension, step_.dxdt.begin());
}

template <class State>
void GslRk8pd<State>::state_at(StateRhs<State> rhs, double t, State& x) {
  step_.state_at(t, x, [&](State& out) {
    gsl_odeiv2_system system = bind(rhs);
    out = step_.x_old;
    State error;
    gsl_odeiv2_step_apply(restep_.get(), step_.t_old, t - step_.t_old, out.data(), error.data(),
                          step_.dxdt_old.data(), nullptr, &system);
  });
}

#define IMPACTLAB_DECLARE_RK8PD(N) extern template class GslRk8pd<std::array<double, N>>;
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DECLARE_RK8PD)
#undef IMPACTLAB_DECLARE_RK8PD

}  // namespace impactlab
