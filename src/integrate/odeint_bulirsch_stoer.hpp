// Bulirsch–Stoer extrapolation with its high-order dense output (Boost.Odeint's
// bulirsch_stoer_dense_out): the high-order method of the Boost backend. Its
// steps may end past the requested limit; the event loop then reads the state
// at the limit from the dense output.
#pragma once

#include <algorithm>

#include <boost/numeric/odeint.hpp>

#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

template <class State>
class OdeintBulirschStoer {
  using Stepper = boost::numeric::odeint::bulirsch_stoer_dense_out<State>;

 public:
  static constexpr const char* name = "bulirsch_stoer";
  static constexpr bool has_cheap_scan = false;  // scan_state cheaper than state_at
  static constexpr bool has_polish = false;

  explicit OdeintBulirschStoer(const StepperSettings& settings)
      : settings_(settings),
        stepper_(settings.atol, settings.rtol, 1.0, 1.0, settings.max_step, true) {}

  template <class Rhs>
  void initialize(const Rhs&, const State& x, double t, double dt) {
    stepper_.initialize(x, t, std::min(dt, settings_.max_step));
  }

  template <class Rhs>
  void do_step(const Rhs& rhs, double /*t_limit*/) {
    stepper_.do_step(rhs);
  }

  void calc_state(double t, State& x) const { stepper_.calc_state(t, x); }

  template <class Rhs>
  void state_at(const Rhs&, double t, State& x) const { calc_state(t, x); }

  // the event scan uses the same dense output
  template <class Rhs>
  void scan_state(const Rhs&, double t, State& x) const { calc_state(t, x); }

  template <class Rhs>
  void polish_state(const Rhs&, double t, State& x) { calc_state(t, x); }

  [[nodiscard]] double previous_time() const { return stepper_.previous_time(); }
  [[nodiscard]] double current_time() const { return stepper_.current_time(); }
  [[nodiscard]] const State& current_state() const { return stepper_.current_state(); }
  [[nodiscard]] const State& previous_state() const { return stepper_.previous_state(); }
  [[nodiscard]] double suggested_step() const { return stepper_.current_time_step(); }

 private:
  StepperSettings settings_;
  mutable Stepper stepper_;
};

}  // namespace impactlab
