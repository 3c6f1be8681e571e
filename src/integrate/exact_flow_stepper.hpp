// The "stepper" of method = "exact": a system's closed-form flow between
// events. It advances by the system's largest step (so the event locator still
// samples the witnesses finely enough) and its dense output is the flow itself.
#pragma once

#include <algorithm>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/stepper_settings.hpp>

namespace impactlab {

template <class System>
  requires HasExactFlow<System>
class ExactFlowStepper {
  using State = typename System::State;

 public:
  static constexpr const char* name = "exact";
  static constexpr bool has_cheap_scan = false;  // scan_state cheaper than state_at
  static constexpr bool has_polish = false;

  explicit ExactFlowStepper(const StepperSettings& settings) : settings_(settings) {}

  void initialize(const ModeRhs<System>& rhs, const State& x, double t, double /*dt*/) {
    rhs_ = rhs;
    x_ = x;
    t_ = t;
  }

  void do_step(const ModeRhs<System>& rhs, double t_limit) {
    rhs_ = rhs;
    x_old_ = x_;
    t_old_ = t_;
    t_ = std::min(t_limit, t_old_ + settings_.max_step);
    rhs_.system->exact_flow(rhs_.mode, x_old_, t_old_, t_, x_);
  }

  void calc_state(double t, State& x) const {
    rhs_.system->exact_flow(rhs_.mode, x_old_, t_old_, t, x);
  }

  template <class Rhs>
  void state_at(const Rhs&, double t, State& x) const { calc_state(t, x); }

  // the event scan uses the same dense output
  template <class Rhs>
  void scan_state(const Rhs&, double t, State& x) const { calc_state(t, x); }

  void polish_state(const ModeRhs<System>&, double t, State& x) { calc_state(t, x); }

  [[nodiscard]] double previous_time() const { return t_old_; }
  [[nodiscard]] double current_time() const { return t_; }
  [[nodiscard]] const State& current_state() const { return x_; }
  [[nodiscard]] const State& previous_state() const { return x_old_; }
  [[nodiscard]] double suggested_step() const { return settings_.max_step; }

 private:
  StepperSettings settings_;
  ModeRhs<System> rhs_{};
  State x_{}, x_old_{};
  double t_ = 0.0, t_old_ = 0.0;
};

}  // namespace impactlab
