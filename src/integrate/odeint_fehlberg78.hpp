// Runge–Kutta–Fehlberg 7(8) (Boost.Odeint's runge_kutta_fehlberg78 under
// controlled_runge_kutta): a 13-stage 8th-order method, inlined like every
// Odeint stepper (no function pointer per evaluation, unlike GSL). It has no
// continuous extension: as for GSL's rk8pd, the event scan uses the cubic
// Hermite interpolant of the step (one extra evaluation per step gives the
// end derivative, which is also the next step's first stage) and every
// refinement re-takes the step itself from the step's start.
#pragma once

#include <algorithm>
#include <cmath>
#include <array>

#include <boost/numeric/odeint.hpp>

#include "integrate/cubic_hermite.hpp"
#include "integrate/step_to_limit.hpp"
#include "integrate/stepper_settings.hpp"

namespace impactlab {

template <class State>
class OdeintFehlberg78 {
  using ErrorStepper = boost::numeric::odeint::runge_kutta_fehlberg78<State>;
  using Controlled = boost::numeric::odeint::controlled_runge_kutta<ErrorStepper>;

 public:
  static constexpr const char* name = "rkf78";
  static constexpr bool has_cheap_scan = true;  // scan_state cheaper than state_at
  static constexpr bool has_polish = false;     // state_at is the step itself

  // defined in odeint_fehlberg78.cpp for the states used here
  explicit OdeintFehlberg78(const StepperSettings& settings);

  template <class Rhs>
  void initialize(const Rhs& rhs, const State& x, double t, double dt) {
    x_ = x;
    t_ = t;
    dt_ = std::min(dt, settings_.max_step);
    rhs(x_, dxdt_, t_);
  }

  // One accepted step, never past t_limit.
  template <class Rhs>
  void do_step(const Rhs& rhs, double t_limit) {
    t_last_ = NAN;  // the last re-taken state belongs to the previous step
    x_old_ = x_;
    dxdt_old_ = dxdt_;
    t_old_ = t_;
    t_ = step_to_limit(t_old_, t_limit, settings_.max_step, dt_, name, [&](double& t, double& dt) {
      return controlled_.try_step(rhs, x_old_, dxdt_old_, t, x_, dt);
    });
    rhs(x_, dxdt_, t_);
  }

  // The state at t inside the last step: the 8th-order step re-taken from
  // the step's start.
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
    controlled_.stepper().do_step(rhs, x_old_, dxdt_old_, t_old_, x, t - t_old_);
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
  Controlled controlled_;
  State x_{}, x_old_{}, dxdt_{}, dxdt_old_{};
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0;
  double t_last_ = NAN;  // time of the last re-taken state (the event
  State x_last_{};       // refinement asks for its final time twice)
};

template <class State>
OdeintFehlberg78<State>::OdeintFehlberg78(const StepperSettings& settings)
    : settings_(settings),
      controlled_(typename Controlled::error_checker_type(settings.atol, settings.rtol),
                  typename Controlled::step_adjuster_type(settings.max_step)) {}

// the constructor for the one-degree-of-freedom states, {q, q̇} and {θ, θ̇, W_f},
// is compiled in odeint_fehlberg78.cpp only (the rest stays inline)
extern template OdeintFehlberg78<std::array<double, 2>>::OdeintFehlberg78(
    const StepperSettings&);
extern template OdeintFehlberg78<std::array<double, 3>>::OdeintFehlberg78(
    const StepperSettings&);

}  // namespace impactlab
