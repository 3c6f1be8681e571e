// Bulirsch–Stoer extrapolation with its high-order dense output (Boost.Odeint's
// bulirsch_stoer_dense_out): the high-order method of the Boost backend. Its
// steps may end past the requested limit; the event loop then reads the state
// at the limit from the dense output. It calls the right-hand side through a
// view (integrate/state_rhs.hpp), so that it is compiled once per state
// type, in odeint_bulirsch_stoer.cpp for the states of
// integrate/state_dimensions.hpp.
#pragma once

#include <algorithm>

#include <boost/numeric/odeint.hpp>

#include <impactlab/integrate/state_dimensions.hpp>
#include <impactlab/integrate/state_rhs.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

template <class State>
class OdeintBulirschStoer {
  using Stepper = boost::numeric::odeint::bulirsch_stoer_dense_out<State>;

 public:
  static constexpr const char* name = "bulirsch_stoer";
  static constexpr bool has_cheap_scan = false;  // scan_state cheaper than state_at
  static constexpr bool has_polish = false;

  explicit OdeintBulirschStoer(const StepperSettings& settings);

  void initialize(StateRhs<State> rhs, const State& x, double t, double dt);

  void do_step(StateRhs<State> rhs, double t_limit);

  void calc_state(double t, State& x) const;

  void state_at(StateRhs<State>, double t, State& x) const { calc_state(t, x); }

  // the event scan uses the same dense output
  void scan_state(StateRhs<State>, double t, State& x) const { calc_state(t, x); }

  void polish_state(StateRhs<State>, double t, State& x) { calc_state(t, x); }

  [[nodiscard]] double previous_time() const { return stepper_.previous_time(); }
  [[nodiscard]] double current_time() const { return stepper_.current_time(); }
  [[nodiscard]] const State& current_state() const { return stepper_.current_state(); }
  [[nodiscard]] const State& previous_state() const { return stepper_.previous_state(); }
  [[nodiscard]] double suggested_step() const { return stepper_.current_time_step(); }

 private:
  StepperSettings settings_;
  mutable Stepper stepper_;
};

template <class State>
OdeintBulirschStoer<State>::OdeintBulirschStoer(const StepperSettings& settings)
    : settings_(settings), stepper_(settings.atol, settings.rtol, 1.0, 1.0, settings.max_step, true) {}

template <class State>
void OdeintBulirschStoer<State>::initialize(StateRhs<State>, const State& x, double t, double dt) {
  stepper_.initialize(x, t, std::min(dt, settings_.max_step));
}

template <class State>
void OdeintBulirschStoer<State>::do_step(StateRhs<State> rhs, double /*t_limit*/) {
  stepper_.do_step(rhs);
}

template <class State>
void OdeintBulirschStoer<State>::calc_state(double t, State& x) const {
  stepper_.calc_state(t, x);
}

#define IMPACTLAB_DECLARE_BULIRSCH_STOER(N) \
  extern template class OdeintBulirschStoer<std::array<double, N>>;
IMPACTLAB_FOR_EACH_STATE_DIMENSION(IMPACTLAB_DECLARE_BULIRSCH_STOER)
#undef IMPACTLAB_DECLARE_BULIRSCH_STOER

}  // namespace impactlab
