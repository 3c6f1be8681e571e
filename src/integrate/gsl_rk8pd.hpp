// GSL's explicit embedded Runge–Kutta Prince–Dormand 8(9) (gsl_odeiv2_step_rk8pd)
// with GSL's standard step control. GSL offers no continuous extension for
// rk8pd, so the state inside a step is the rk8pd step itself re-taken from the
// step's start to the requested time: 8th-order accurate, at 13 evaluations.
// The event locator's coarse scan of a step only has to find where to look,
// so it uses the cubic Hermite interpolant of the step's end states and
// derivatives (which GSL's evolve has already computed: no evaluation), and
// every refinement uses the re-taken step.
#pragma once

#include <algorithm>
#include <cmath>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include "integrate/cubic_hermite.hpp"
#include "integrate/stepper_settings.hpp"

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
  // bound mode's functor as its parameter block.
  template <class Rhs>
  static int gsl_rhs(double t, const double y[], double dydt[], void* params) {
    const auto& rhs = *static_cast<const Rhs*>(params);
    State x;
    std::copy_n(y, dimension, x.begin());
    State dxdt;
    rhs(x, dxdt, t);
    std::copy_n(dxdt.begin(), dimension, dydt);
    return GSL_SUCCESS;
  }

  template <class Rhs>
  gsl_odeiv2_system bind(const Rhs& rhs) const {
    return gsl_odeiv2_system{&gsl_rhs<Rhs>, nullptr, dimension,
                             const_cast<void*>(static_cast<const void*>(&rhs))};
  }

 public:
  static constexpr const char* name = "rk8pd";
  static constexpr bool has_cheap_scan = true;  // scan_state cheaper than state_at
  static constexpr bool has_polish = false;

  explicit GslRk8pd(const StepperSettings& settings)
      : settings_(settings),
        step_(gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, dimension)),
        restep_(gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, dimension)),
        control_(gsl_odeiv2_control_standard_new(settings.atol, settings.rtol, 1.0, 0.0)),
        evolve_(gsl_odeiv2_evolve_alloc(dimension)) {
    if (!step_ || !restep_ || !control_ || !evolve_)
      throw std::runtime_error("rk8pd: GSL allocation failed");
  }

  template <class Rhs>
  void initialize(const Rhs&, const State& x, double t, double dt) {
    x_ = x;
    t_ = t;
    dt_ = std::min(dt, settings_.max_step);
    gsl_odeiv2_evolve_reset(evolve_.get());
    gsl_odeiv2_step_reset(step_.get());
  }

  template <class Rhs>
  void do_step(const Rhs& rhs, double t_limit) {
    t_last_ = NAN;  // the last re-taken state belongs to the previous step
    x_old_ = x_;
    t_old_ = t_;
    gsl_odeiv2_system system = bind(rhs);
    const double t_stop = std::min(t_limit, t_old_ + settings_.max_step);
    double t = t_old_;
    const int status = gsl_odeiv2_evolve_apply(evolve_.get(), control_.get(), step_.get(),
                                               &system, &t, t_stop, &dt_, x_.data());
    if (status != GSL_SUCCESS)
      throw std::runtime_error("rk8pd: gsl_odeiv2_evolve_apply failed: " +
                               std::string(gsl_strerror(status)));
    t_ = t;
    dt_ = std::min(dt_, settings_.max_step);
    // the derivatives at both ends of the accepted step, as evolve computed them
    std::copy_n(evolve_->dydt_in, dimension, dxdt_old_.begin());
    std::copy_n(evolve_->dydt_out, dimension, dxdt_.begin());
  }

  // The state at t inside the last step: the rk8pd step re-taken from the
  // step's start (needs the functor of the last step).
  template <class Rhs>
  void state_at(const Rhs& rhs, double t, State& x) {
    if (t == t_) {
      x = x_;
      return;
    }
    if (t == t_last_) {
      x = x_last_;
      return;
    }
    gsl_odeiv2_system system = bind(rhs);
    x = x_old_;
    State error;
    gsl_odeiv2_step_apply(restep_.get(), t_old_, t - t_old_, x.data(), error.data(),
                          dxdt_old_.data(), nullptr, &system);
    t_last_ = t;
    x_last_ = x;
  }

  template <class Rhs>
  void polish_state(const Rhs& rhs, double t, State& x) { state_at(rhs, t, x); }

  // cubic Hermite interpolant of the last step (for the event scan only)
  template <class Rhs>
  void scan_state(const Rhs&, double t, State& x) const {
    cubic_hermite(t_old_, x_old_, dxdt_old_, t_, x_, dxdt_, t, x);
  }

  [[nodiscard]] double previous_time() const { return t_old_; }
  [[nodiscard]] double current_time() const { return t_; }
  [[nodiscard]] const State& current_state() const { return x_; }
  [[nodiscard]] const State& previous_state() const { return x_old_; }
  [[nodiscard]] double suggested_step() const { return dt_; }

 private:
  StepperSettings settings_;
  std::unique_ptr<gsl_odeiv2_step, StepDeleter> step_, restep_;
  std::unique_ptr<gsl_odeiv2_control, ControlDeleter> control_;
  std::unique_ptr<gsl_odeiv2_evolve, EvolveDeleter> evolve_;
  State x_{}, x_old_{}, dxdt_{}, dxdt_old_{};
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0;
  double t_last_ = NAN;  // time of the last re-taken state (the event
  State x_last_{};       // refinement asks for its final time twice)
};

}  // namespace impactlab
