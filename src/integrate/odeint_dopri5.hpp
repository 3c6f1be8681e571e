// Dormand–Prince 5(4) with its 4th-order continuous extension (Boost.Odeint's
// runge_kutta_dopri5 under controlled_runge_kutta), driven step by step so the
// event loop can clip a step at the end time, read the dense output, and
// re-evaluate the 5th-order step to an event time ("polish"). It calls the
// right-hand side through a view (integrate/state_rhs.hpp), so that it is
// compiled once per state type, in odeint_dopri5.cpp for the states of
// integrate/state_dimensions.hpp.
#pragma once

#include <algorithm>

#include <boost/numeric/odeint.hpp>

#include <impactlab/integrate/state_dimensions.hpp>
#include <impactlab/integrate/state_rhs.hpp>
#include <impactlab/integrate/step_to_limit.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

template <class State>
class OdeintDopri5 {
  using ErrorStepper = boost::numeric::odeint::runge_kutta_dopri5<State>;
  using Controlled = boost::numeric::odeint::controlled_runge_kutta<ErrorStepper>;

 public:
  static constexpr const char* name = "dopri5";
  static constexpr bool has_cheap_scan = false;  // scan_state cheaper than state_at
  static constexpr bool has_polish = true;

  explicit OdeintDopri5(const StepperSettings& settings);

  void initialize(StateRhs<State> rhs, const State& x, double t, double dt);

  // One accepted step, never past t_limit.
  void do_step(StateRhs<State> rhs, double t_limit);

  // Dense output inside the last step (4th order).
  void calc_state(double t, State& x) const;

  void state_at(StateRhs<State>, double t, State& x) const { calc_state(t, x); }

  // the event scan uses the same dense output
  void scan_state(StateRhs<State>, double t, State& x) const { calc_state(t, x); }

  // The 5th-order step from the last step's start to t: what the integrator
  // itself would give had it stepped to t.
  void polish_state(StateRhs<State> rhs, double t, State& x);

  [[nodiscard]] double previous_time() const { return t_old_; }
  [[nodiscard]] double current_time() const { return t_; }
  [[nodiscard]] const State& current_state() const { return x_; }
  [[nodiscard]] const State& previous_state() const { return x_old_; }
  [[nodiscard]] double suggested_step() const { return dt_; }

 private:
  StepperSettings settings_;
  Controlled controlled_;
  ErrorStepper polisher_;
  State x_{}, x_old_{}, dxdt_{}, dxdt_old_{};
  double t_ = 0.0, t_old_ = 0.0, dt_ = 0.0;
};

template <class State>
OdeintDopri5<State>::OdeintDopri5(const StepperSettings& settings)
    : settings_(settings),
      controlled_(typename Controlled::error_checker_type(settings.atol, settings.rtol),
                  typename Controlled::step_adjuster_type(settings.max_step)) {}

template <class State>
void OdeintDopri5<State>::initialize(StateRhs<State> rhs, const State& x, double t, double dt) {
  x_ = x;
  t_ = t;
  dt_ = std::min(dt, settings_.max_step);
  rhs(x_, dxdt_, t_);
}

template <class State>
void OdeintDopri5<State>::do_step(StateRhs<State> rhs, double t_limit) {
  x_old_ = x_;
  dxdt_old_ = dxdt_;
  t_old_ = t_;
  t_ = step_to_limit(t_old_, t_limit, settings_.max_step, dt_, name, [&](double& t, double& dt) {
    return controlled_.try_step(rhs, x_old_, dxdt_old_, t, x_, dxdt_, dt);
  });
}

template <class State>
void OdeintDopri5<State>::calc_state(double t, State& x) const {
  controlled_.stepper().calc_state(t, x, x_old_, dxdt_old_, t_old_, x_, dxdt_, t_);
}

template <class State>
void OdeintDopri5<State>::polish_state(StateRhs<State> rhs, double t, State& x) {
  State dxdt_end;
  polisher_.do_step(rhs, x_old_, dxdt_old_, t_old_, x, dxdt_end, t - t_old_);
}

#define IMPACTLAB_DECLARE_DOPRI5(N) extern template class OdeintDopri5<std::array<double, N>>;
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DECLARE_DOPRI5)
#undef IMPACTLAB_DECLARE_DOPRI5

}  // namespace impactlab
