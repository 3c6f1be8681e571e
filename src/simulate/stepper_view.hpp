// A stepper seen through one virtual call per use, so that the event loop
// (simulate/simulator.hpp) is compiled once per system, not once per system
// and stepper.
//
// The engines of simulate/flow_engines.hpp run the loop on a SteppingView of
// their stepper. It costs a few indirect calls per step: the step, its
// times and end state, and the event location (the Taylor stepper's own, or
// for the other steppers the loop's scan of their dense output, one call per
// sample). None is made per right-hand-side evaluation: the stepper calls the
// right-hand side directly.
#pragma once

#include <cstddef>
#include <stdexcept>

#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/event_location.hpp>
#include <impactlab/integrate/stepper_settings.hpp>
#include <impactlab/simulate/dense_output_stepper.hpp>

namespace impactlab {

// The members of the dense-output stepper concept
// (simulate/dense_output_stepper.hpp) and of its own event location
// (LocatesItsOwnEvents), dispatched at run time; the flags are read once,
// when the view is made.
template <HybridSystem System>
class SteppingView {
 public:
  using State = typename System::State;
  using Mode = typename System::Mode;
  using Rhs = ModeRhs<System>;

  SteppingView(const SteppingView&) = delete;
  SteppingView& operator=(const SteppingView&) = delete;

  [[nodiscard]] bool scans_cheaply() const { return scans_cheaply_; }
  [[nodiscard]] bool polishes() const { return polishes_; }
  // false: the loop scans the dense output for events, and never calls
  // locate_first_event
  [[nodiscard]] bool locates_own_events() const { return locates_own_events_; }

  virtual void initialize(const Rhs& rhs, const State& x, double t, double dt) = 0;
  virtual void do_step(const Rhs& rhs, double t_limit) = 0;
  virtual void state_at(const Rhs& rhs, double t, State& x) = 0;
  virtual void scan_state(const Rhs& rhs, double t, State& x) = 0;
  virtual void polish_state(const Rhs& rhs, double t, State& x) = 0;
  [[nodiscard]] virtual double previous_time() const = 0;
  [[nodiscard]] virtual double current_time() const = 0;
  [[nodiscard]] virtual const State& previous_state() const = 0;
  [[nodiscard]] virtual const State& current_state() const = 0;
  [[nodiscard]] virtual double suggested_step() const = 0;
  [[nodiscard]] virtual LocatedEvent locate_first_event(const System& system, Mode mode,
                                                        double ta, double tb,
                                                        const EventLocationOptions& options,
                                                        std::size_t just_grazed) const = 0;

 protected:
  SteppingView(bool scans_cheaply, bool polishes, bool locates_own_events)
      : scans_cheaply_(scans_cheaply),
        polishes_(polishes),
        locates_own_events_(locates_own_events) {}
  ~SteppingView() = default;

 private:
  bool scans_cheaply_;
  bool polishes_;
  bool locates_own_events_;
};

// Stepper behind the view: it owns the stepper and forwards each member.
template <HybridSystem System, class Stepper>
class SteppingViewOf final : public SteppingView<System> {
 public:
  using State = typename System::State;
  using Mode = typename System::Mode;
  using Rhs = ModeRhs<System>;

  explicit SteppingViewOf(const StepperSettings& settings)
      : SteppingView<System>(Stepper::has_cheap_scan, Stepper::has_polish,
                             LocatesItsOwnEvents<Stepper, System>),
        stepper_(settings) {}

  void initialize(const Rhs& rhs, const State& x, double t, double dt) override {
    stepper_.initialize(rhs, x, t, dt);
  }
  void do_step(const Rhs& rhs, double t_limit) override { stepper_.do_step(rhs, t_limit); }
  void state_at(const Rhs& rhs, double t, State& x) override { stepper_.state_at(rhs, t, x); }
  void scan_state(const Rhs& rhs, double t, State& x) override { stepper_.scan_state(rhs, t, x); }
  void polish_state(const Rhs& rhs, double t, State& x) override {
    stepper_.polish_state(rhs, t, x);
  }
  [[nodiscard]] double previous_time() const override { return stepper_.previous_time(); }
  [[nodiscard]] double current_time() const override { return stepper_.current_time(); }
  [[nodiscard]] const State& previous_state() const override { return stepper_.previous_state(); }
  [[nodiscard]] const State& current_state() const override { return stepper_.current_state(); }
  [[nodiscard]] double suggested_step() const override { return stepper_.suggested_step(); }
  [[nodiscard]] LocatedEvent locate_first_event(const System& system, Mode mode, double ta,
                                                double tb, const EventLocationOptions& options,
                                                std::size_t just_grazed) const override {
    if constexpr (LocatesItsOwnEvents<Stepper, System>)
      return stepper_.locate_first_event(system, mode, ta, tb, options, just_grazed);
    else
      throw std::logic_error("the event loop scans this stepper's steps for events itself");
  }

 private:
  Stepper stepper_;
};

}  // namespace impactlab
