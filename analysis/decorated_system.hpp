// A hybrid system with what the analyses add to it, each switched on at run
// time, one type for all of them:
//
// * a crossing section: the crossings of q = c or q̇ = c in a chosen
//   direction, as one more witness whose event changes nothing and records
//   the crossing (Poincaré sections on a level, analysis/run_section.hpp);
// * suppressed contacts: witness `window.witness` does not fire in flight
//   mode between the absolute times window.from and window.to (it reads +1
//   there), and every crossing in flight mode is noted (the grazing extended
//   system of continuation, analysis/map_evaluation.hpp);
// * a stop at a wall impact: the run stops just before the reset of the
//   `target`-th impact with wall `wall` (counted from 0, a run that starts on
//   the wall moving into it has that impact as its 0th), noting the times of
//   those impacts (the impact map of continuation, analysis/impact_map_problem.hpp).
//   The log must keep its
//   records: the wall of an impact is read from them.
//
// With nothing switched on it is its base: the same witnesses, values,
// events and Jacobians, number for number, so the analyses run one
// decorated type per oscillator (and its variational equations) instead of
// one type per combination of decorations, and the program compiles the
// event loop for a few system types per oscillator, not for every
// combination (analysis/analysis_flows.hpp). Everything not decorated is
// forwarded to the base, each optional member where the base has it.
#pragma once

#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <string_view>
#include <vector>

#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/core/error_scale_groups.hpp>
#include <impactlab/core/state_names.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace impactlab {

// What the decoration saw of the crossings in flight mode during one run.
struct CrossingTrace {
  struct Crossing {
    double t;      // s
    int witness;
    double speed;  // |witness rate| just before (the normal approach speed)
  };
  std::vector<Crossing> crossings;
  // the flight witness of the last impact whose tangent map is one side's
  // (an impulse on the friction cone's edge, ResetJacobianOf::one_sided);
  // −1: none
  int one_sided_witness = -1;
};

// What the stop at a wall impact saw of the impacts with its wall during one run.
struct WallImpactTrace {
  std::vector<double> times;     // every impact with the wall (s), in order
  bool stopped = false;          // the run stopped at the target impact
  double stop_time = 0.0;        // s
  std::size_t stop_witness = 0;  // the witness whose crossing it was
  std::size_t first_record = 0, stop_record = 0;  // log indices of the first and the target impact
};

template <class Base>
constexpr bool affine_flow_of() {
  if constexpr (requires { Base::affine_flow; }) return Base::affine_flow;
  return false;
}

template <HybridSystem Base>
class DecoratedSystem {
 public:
  using State = typename Base::State;
  using Mode = typename Base::Mode;
  // the crossing section's witness comes after the base's
  static constexpr std::size_t max_witnesses = Base::max_witnesses + 1;
  static constexpr bool affine_flow = affine_flow_of<Base>();
  static constexpr std::size_t tangent_dimension = tangent_dimension_of<Base>;
  static constexpr ErrorScaleGroupsOf<Base> error_scale_groups = error_scale_groups_of<Base>();

  // a view of `base`, which outlives it: a decorated system is made for a
  // run or an analysis, often once per run, and copies nothing
  explicit DecoratedSystem(const Base& base) : base_(&base) {}

  // points: where the crossings go (the caller's)
  DecoratedSystem& with_crossing_section(const SectionSpec& section, SectionPoints& points) {
    section_ = section;
    points_ = &points;
    decorated_ = true;
    return *this;
  }
  // trace: where the crossings in flight mode go, or null
  DecoratedSystem& with_suppressed_contacts(Mode flight_mode, const ContactWindow& window,
                                            CrossingTrace* trace) {
    suppressing_ = true;
    decorated_ = true;
    flight_mode_ = flight_mode;
    window_ = window;
    crossings_ = trace;
    return *this;
  }
  DecoratedSystem& with_stop_at_wall_impact(int wall, int target, WallImpactTrace& trace) {
    stop_wall_ = wall;
    stop_target_ = target;
    wall_impacts_ = &trace;
    decorated_ = true;
    return *this;
  }

  [[nodiscard]] const Base& base() const { return *base_; }
  [[nodiscard]] double max_step() const { return base_->max_step(); }
  [[nodiscard]] std::vector<std::string_view> state_names() const
    requires HasStateNames<Base>
  {
    return base_->state_names();
  }

  // over the base's number types (a series type runs through it where it
  // runs through the base)
  template <class Vector, class Number>
    requires requires(const Base& base, Mode mode, const Vector& x, Vector& dxdt,
                      const Number& t) { base.rhs(mode, x, dxdt, t); }
  void rhs(Mode mode, const Vector& x, Vector& dxdt, const Number& t) const {
    base_->rhs(mode, x, dxdt, t);
  }

  [[nodiscard]] std::size_t witness_count(Mode mode) const {
    return base_->witness_count(mode) + (points_ ? 1 : 0);
  }
  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    // every crossing of the section is an event (a one-sided trigger would
    // count the state left on its far side as a missed root); on_event keeps
    // the wanted ones
    if (is_section_witness(mode, k)) return TriggerDirection::either;
    return base_->trigger_direction(mode, k);
  }

  [[nodiscard]] bool suppressed(Mode mode, std::size_t k, double t) const {
    return suppressing_ && mode == flight_mode_ && static_cast<int>(k) == window_.witness &&
           t >= window_.from && t <= window_.to;
  }

  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& x, double t) const {
    if (!decorated_) return base_->witness(mode, k, x, t);
    if (is_section_witness(mode, k)) return section_witness(mode, x, t);
    if (suppressed(mode, k, t)) return {1.0, 0.0};
    return base_->witness(mode, k, x, t);
  }
  // Over a series type: the window's ends end the Taylor stepper's steps
  // (witness_switch_after), so each step lies inside the window or outside
  // it, and its start time decides (from <= start < to).
  template <class Vector, class Number>
    requires(!std::same_as<Number, double>) &&
            requires(const Base& base, Mode mode, std::size_t k, const Vector& x,
                     const Number& t) { base.witness(mode, k, x, t); }
  [[nodiscard]] auto witness(Mode mode, std::size_t k, const Vector& x, const Number& t) const
      -> BasicWitnessSample<Number> {
    // one test per witness and order where nothing is switched on (the
    // system's own flows run so)
    if (!decorated_) return base_->witness(mode, k, x, t);
    if constexpr (requires(Vector& dxdt) { base_->rhs(mode, x, dxdt, t); }) {
      if (is_section_witness(mode, k)) return section_witness(mode, x, t);
    }
    const double start = start_value(t);
    if (suppressed(mode, k, start) && start != window_.to) return {Number(1.0), Number(0.0)};
    return base_->witness(mode, k, x, t);
  }

  // the first end of the suppression window after t (s), or +∞
  [[nodiscard]] double witness_switch_after(double t) const {
    if (!suppressing_ || window_.witness < 0) return std::numeric_limits<double>::infinity();
    if (t < window_.from) return window_.from;
    if (t < window_.to) return window_.to;
    return std::numeric_limits<double>::infinity();
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing, const State& x,
                                   double t, EventLog& log) const {
    if (is_section_witness(mode, k)) {
      const double rate = witness(mode, k, x, t).rate;
      const bool wanted =
          section_.direction == 0 || (section_.direction > 0 ? rate > 0.0 : rate < 0.0);
      if (crossing == CrossingKind::crossing && wanted) points_->add({t, x[0], x[1], 0});
      return {x, mode, t, false};
    }
    if (crossings_ && crossing == CrossingKind::crossing && mode == flight_mode_)
      crossings_->crossings.push_back(
          {t, static_cast<int>(k), std::fabs(base_->witness(mode, k, x, t).rate)});
    if (wall_impacts_ == nullptr) return base_->on_event(mode, k, crossing, x, t, log);
    // the records the base's event adds: is one of them an impact with the wall?
    const std::size_t before = log.records().size();
    auto after = base_->on_event(mode, k, crossing, x, t, log);
    const auto& records = log.records();
    for (std::size_t j = before; j < records.size(); ++j) {
      if (records[j].kind != EventKind::impact || records[j].wall != stop_wall_) continue;
      const int index = static_cast<int>(wall_impacts_->times.size());
      wall_impacts_->times.push_back(t);
      if (index == 0) wall_impacts_->first_record = j;
      if (index == stop_target_) {
        wall_impacts_->stopped = true;
        wall_impacts_->stop_time = t;
        wall_impacts_->stop_witness = k;
        wall_impacts_->stop_record = j;
        return {x, mode, t, true};  // the state just before the impact
      }
      break;
    }
    return after;
  }

  void exact_flow(Mode mode, const State& x0, double t0, double t, State& x) const
    requires HasExactFlow<Base>
  {
    base_->exact_flow(mode, x0, t0, t, x);
  }

  // the Jacobians of the base's witnesses (the section's witness has none:
  // a section and the variational equations are not run together)
  void jacobian(Mode mode, const State& x, double t, TangentMatrixOf<tangent_dimension>& j) const
    requires HasJacobian<Base>
  {
    base_->jacobian(mode, x, t, j);
  }
  [[nodiscard]] TangentVectorOf<tangent_dimension> witness_gradient(Mode mode, std::size_t k,
                                                                    const State& x,
                                                                    double t) const
    requires HasJacobian<Base>
  {
    if (suppressed(mode, k, t)) return {};
    return base_->witness_gradient(mode, k, x, t);
  }
  [[nodiscard]] ResetJacobianOf<tangent_dimension> reset_jacobian(
      Mode mode, std::size_t k, CrossingKind crossing, const State& x, double t,
      const Transition<State, Mode>& after) const
    requires HasJacobian<Base>
  {
    auto jacobian = base_->reset_jacobian(mode, k, crossing, x, t, after);
    if (crossings_ && jacobian.one_sided && mode == flight_mode_)
      crossings_->one_sided_witness = static_cast<int>(k);
    return jacobian;
  }
  [[nodiscard]] bool pinned(Mode mode) const
    requires HasJacobian<Base>
  {
    return base_->pinned(mode);
  }
  [[nodiscard]] TangentVectorOf<tangent_dimension> pinned_components(Mode mode) const
    requires HasJacobian<Base> && requires(const Base& base) { base.pinned_components(mode); }
  {
    return base_->pinned_components(mode);
  }

 private:
  [[nodiscard]] bool is_section_witness(Mode mode, std::size_t k) const {
    return points_ != nullptr && k == base_->witness_count(mode);
  }
  // x[component] − c, its rate from the vector field (over the base's number types)
  template <class Vector, class Number>
  [[nodiscard]] BasicWitnessSample<Number> section_witness(Mode mode, const Vector& x,
                                                           const Number& t) const {
    Vector dxdt;
    base_->rhs(mode, x, dxdt, t);
    const std::size_t component = section_.kind == SectionKind::q_crossing ? 0 : 1;
    return {x[component] - section_.level, dxdt[component]};
  }

  const Base* base_;
  // whether anything is switched on
  bool decorated_ = false;
  // the crossing section, where points_ is set
  SectionSpec section_{};
  SectionPoints* points_ = nullptr;
  // the suppressed contacts, where suppressing_
  bool suppressing_ = false;
  Mode flight_mode_{};
  ContactWindow window_{};
  CrossingTrace* crossings_ = nullptr;
  // the stop at a wall impact, where wall_impacts_ is set
  int stop_wall_ = 0, stop_target_ = -1;
  WallImpactTrace* wall_impacts_ = nullptr;
};

}  // namespace impactlab
