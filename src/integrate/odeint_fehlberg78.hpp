// Runge–Kutta–Fehlberg 7(8) (Boost.Odeint's runge_kutta_fehlberg78 under
// controlled_runge_kutta): a 13-stage 8th-order method, inlined like every
// Odeint stepper (no function pointer per evaluation, unlike GSL). It has no
// continuous extension: as for GSL's rk8pd, the event scan uses the cubic
// Hermite interpolant of the step (one extra evaluation per step gives the
// end derivative, which is also the next step's first stage) and every
// refinement re-takes the step itself from the step's start.
#pragma once

#include <algorithm>
#include <array>

#include <boost/numeric/odeint.hpp>

#include <impactlab/integrate/state_dimensions.hpp>
#include <impactlab/integrate/step_record.hpp>
#include <impactlab/integrate/step_to_limit.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

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
    step_.x = x;
    step_.t = t;
    dt_ = std::min(dt, settings_.max_step);
    rhs(step_.x, step_.dxdt, step_.t);
  }

  // One accepted step, never past t_limit.
  template <class Rhs>
  void do_step(const Rhs& rhs, double t_limit) {
    step_.begin_step();
    step_.t = step_to_limit(step_.t_old, t_limit, settings_.max_step, dt_, name,
                            [&](double& t, double& dt) {
                              return controlled_.try_step(rhs, step_.x_old, step_.dxdt_old, t,
                                                          step_.x, dt);
                            });
    rhs(step_.x, step_.dxdt, step_.t);
  }

  // The state at t inside the last step: the 8th-order step re-taken from
  // the step's start.
  template <class Rhs>
  void state_at(const Rhs& rhs, double t, State& x) {
    step_.state_at(t, x, [&](State& out) {
      controlled_.stepper().do_step(rhs, step_.x_old, step_.dxdt_old, step_.t_old, out,
                                    t - step_.t_old);
    });
  }

  template <class Rhs>
  void polish_state(const Rhs& rhs, double t, State& x) { state_at(rhs, t, x); }

  template <class Rhs>
  void scan_state(const Rhs&, double t, State& x) const { step_.interpolate(t, x); }

  [[nodiscard]] double previous_time() const { return step_.t_old; }
  [[nodiscard]] double current_time() const { return step_.t; }
  [[nodiscard]] const State& current_state() const { return step_.x; }
  [[nodiscard]] const State& previous_state() const { return step_.x_old; }
  [[nodiscard]] double suggested_step() const { return dt_; }

 private:
  StepperSettings settings_;
  Controlled controlled_;
  StepRecord<State> step_;
  double dt_ = 0.0;  // carried step size (s)
};

template <class State>
OdeintFehlberg78<State>::OdeintFehlberg78(const StepperSettings& settings)
    : settings_(settings),
      controlled_(typename Controlled::error_checker_type(settings.atol, settings.rtol),
                  typename Controlled::step_adjuster_type(settings.max_step)) {}

// the constructor for the states of integrate/state_dimensions.hpp is
// compiled in odeint_fehlberg78.cpp only (the rest stays inline)
#define IMPACTLAB_DECLARE_FEHLBERG78(N) \
  extern template OdeintFehlberg78<std::array<double, N>>::OdeintFehlberg78(const StepperSettings&);
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DECLARE_FEHLBERG78)
#undef IMPACTLAB_DECLARE_FEHLBERG78

}  // namespace impactlab
