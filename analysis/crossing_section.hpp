// A user-given section: the crossings of q = c or q̇ = c (the main coordinate
// or its rate) in a chosen direction, as one more witness added to a hybrid
// system. The added event changes nothing in the state or the mode; it only
// records the crossing (in the chosen direction: the sign of the witness's
// rate there). Everything else is forwarded to the base system.
#pragma once

#include <cstddef>
#include <vector>

#include <impactlab/analysis/section.hpp>
#include <impactlab/core/hybrid_system.hpp>

namespace impactlab {

template <HybridSystem Base>
class CrossingSection {
 public:
  using State = typename Base::State;
  using Mode = typename Base::Mode;
  static constexpr std::size_t max_witnesses = Base::max_witnesses + 1;

  // points: where the crossings go
  CrossingSection(const Base& base, const SectionSpec& section, SectionPoints& points)
      : base_(base), section_(section), points_(&points) {}

  [[nodiscard]] double max_step() const { return base_.max_step(); }
  template <class Vector, class Number>
    requires requires(const Base& base, Mode mode, const Vector& x, Vector& dxdt,
                      const Number& t) { base.rhs(mode, x, dxdt, t); }
  void rhs(Mode mode, const Vector& x, Vector& dxdt, const Number& t) const {
    base_.rhs(mode, x, dxdt, t);
  }

  [[nodiscard]] std::size_t witness_count(Mode mode) const {
    return base_.witness_count(mode) + 1;
  }
  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    if (k < base_.witness_count(mode)) return base_.trigger_direction(mode, k);
    // every crossing is an event (a one-sided trigger would count the state
    // left on its far side as a missed root); on_event keeps the wanted ones
    return TriggerDirection::either;
  }
  // the added witness: x[component] − c, its rate from the vector field
  // (over the base system's number types: a series type runs through it
  // where it runs through the base)
  template <class Vector, class Number>
    requires requires(const Base& base, Mode mode, std::size_t k, const Vector& x, Vector& dxdt,
                      const Number& t) {
      base.rhs(mode, x, dxdt, t);
      base.witness(mode, k, x, t);
    }
  [[nodiscard]] auto witness(Mode mode, std::size_t k, const Vector& x, const Number& t) const
      -> BasicWitnessSample<Number> {
    if (k < base_.witness_count(mode)) return base_.witness(mode, k, x, t);
    Vector dxdt;
    base_.rhs(mode, x, dxdt, t);
    const std::size_t component = section_.kind == SectionKind::q_crossing ? 0 : 1;
    return {x[component] - section_.level, dxdt[component]};
  }

  void exact_flow(Mode mode, const State& x0, double t0, double t, State& x) const
    requires HasExactFlow<Base>
  {
    base_.exact_flow(mode, x0, t0, t, x);
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing,
                                   const State& x, double t, EventLog& log) const {
    if (k < base_.witness_count(mode)) return base_.on_event(mode, k, crossing, x, t, log);
    const double rate = witness(mode, k, x, t).rate;
    const bool wanted = section_.direction == 0 || (section_.direction > 0 ? rate > 0.0 : rate < 0.0);
    if (crossing == CrossingKind::crossing && wanted) points_->add({t, x[0], x[1], 0});
    return {x, mode, t, false};
  }

 private:
  Base base_;
  SectionSpec section_;
  SectionPoints* points_;  // the caller's; given each crossing
};

}  // namespace impactlab
