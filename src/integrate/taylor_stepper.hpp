// The Taylor-series stepper (integrator.method = "taylor"): each step is the
// Taylor polynomial of the solution at the step's start, its coefficients by
// automatic differentiation of the system's own right-hand side
// (integrate/taylor_series.hpp), so the polynomial is the dense output, as
// accurate inside the step as at its end.
//
// Order and step (after Jorba & Zou 2005 and heyoka): the last two
// coefficients estimate the radius of convergence,
// ρ = min over j ∈ {p−1, p} of (s / ‖x_j‖∞)^{1/j}, with s = max(‖x_0‖∞, atol/rtol)
// (relative error where the state is large, absolute where it is small;
// ‖·‖∞ over each group of components, core/error_scale_groups.hpp), and
// the step is the fixed fraction h = ρ · e^{−1.3} · exp(−0.7 / (p − 1)) of it;
// the order p = ⌈−ln ε / 1.3⌉ (ε = rtol) makes the truncation error,
// about (h/ρ)^p s, of order ε s. Jorba & Zou's and heyoka's fraction is e^{−2}
// with p = ⌈−ln ε / 2⌉ + 1, optimal when the series' O(p²) work is the whole
// cost of a step; here each step also costs its restart and event tests,
// and on the pendulum (jin2003, V0 = 1.5) e^{−2} took 16 steps per forcing
// period with errors 100× below the tolerance, e^{−1.3} takes 8 at about the
// tolerance (docs/performance.md). The witnesses' coefficients bound ρ too.
//
// Events (locate_first_event): the witness functions of the mode run through
// the series with the right-hand side, so each has its Taylor polynomial over
// the step.
// A step whose witness polynomial g (oriented so that its trigger is a fall
// through zero) satisfies min(g_0, g_0 + g_1 h) − Σ_{j≥2} |g_j| h^j > the
// grazing tolerance cannot hold an event and is skipped at the cost of one
// sum. In the others,
// the critical points of g are isolated rigorously (integrate/polynomial_event.hpp on
// integrate/polynomial_roots.hpp); on each monotone piece a crossing is bracketed by
// the sign of g at its ends and refined by safeguarded Newton on the
// polynomial (integrate/monotone_root.hpp; in a batch lane, together with
// the other lanes' roots); a minimum within the grazing tolerance is a
// grazing. No sampling and no
// re-taken step: the event loop needs no max_step cap for this stepper.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>

#include <impactlab/core/error_scale_groups.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/event_location.hpp>
#include <impactlab/integrate/polynomial_event.hpp>
#include <impactlab/integrate/series_lane.hpp>
#include <impactlab/integrate/series_tape.hpp>
#include <impactlab/integrate/stepper_settings.hpp>
#include <impactlab/integrate/taylor_series.hpp>

namespace impactlab {

template <class System, class Real = double>
using SeriesState = std::array<TaylorVariable<Real>, std::tuple_size_v<typename System::State>>;

// A system whose right-hand side and witnesses are written over a number
// type, so that TaylorVariable runs through them.
template <class S>
concept HasSeriesRhs = HybridSystem<S> && requires(const S& system, typename S::Mode mode,
                                                   const SeriesState<S>& x, SeriesState<S>& dxdt,
                                                   const TaylorVariable<>& t, std::size_t k) {
  { system.rhs(mode, x, dxdt, t) };
  { system.witness(mode, k, x, t).value } -> std::convertible_to<TaylorVariable<>>;
};

// A system whose right-hand side and witnesses also run over TapeVariable
// (integrate/series_tape.hpp), so that a batch can record its order-0 pass
// and compute several lanes' series in one pass. Other systems' lanes are
// evaluated one after the other, each in double.
template <class S>
concept HasTapeRhs =
    requires(const S& system, typename S::Mode mode,
             const std::array<TapeVariable, std::tuple_size_v<typename S::State>>& x,
             std::array<TapeVariable, std::tuple_size_v<typename S::State>>& dxdt,
             const TapeVariable& t, std::size_t k) {
      { system.rhs(mode, x, dxdt, t) };
      { system.witness(mode, k, x, t).value } -> std::convertible_to<TapeVariable>;
    };

// the fraction of the radius of convergence a step takes: e^{−step_exponent}
inline constexpr double taylor_step_exponent = 1.3;

// the order for a tolerance: ⌈−ln ε / 1.3⌉, within the series' capacity
inline int taylor_order(double tolerance) {
  const double order = std::ceil(-std::log(tolerance) / taylor_step_exponent);
  return static_cast<int>(std::clamp(order, 2.0, static_cast<double>(taylor_max_order)));
}

// Real: the arithmetic of the series, the step's state and time (double; or
// an extended-precision type for a reference run, integrator.method =
// "taylor_quad": the loop still sees doubles, at events and step ends, while
// the steps between events continue from the stepper's own Real state).
template <HasSeriesRhs System, class Real = double>
class TaylorStepper {
 public:
  using State = typename System::State;
  using Mode = typename System::Mode;
  using RealState = std::array<Real, std::tuple_size_v<State>>;
  static constexpr const char* name = "taylor";
  static constexpr bool has_cheap_scan = false;
  static constexpr bool has_polish = true;  // state_at is the step's own polynomial
  static constexpr std::size_t dimension = std::tuple_size_v<State>;

  explicit TaylorStepper(const StepperSettings& settings)
      : settings_(settings),
        order_(taylor_order(settings.rtol)),
        safety_(std::exp(-taylor_step_exponent - 0.7 / (order_ - 1))),
        scale_floor_(settings.atol / settings.rtol) {
    if (!(settings.rtol > 0.0) || !(settings.atol > 0.0))
      throw std::invalid_argument("taylor: rtol and atol must be positive");
  }

  [[nodiscard]] int order() const { return order_; }

  template <class Rhs>
  void initialize(const Rhs& /*rhs*/, const State& x, double t, double /*dt*/) {
    for (std::size_t i = 0; i < dimension; ++i) x_[i] = x[i];
    t_ = t;
    x_double_ = x;
    t_double_ = t;
  }

  // One step from (t_, x_): the Taylor polynomial, the step from its last
  // two coefficients, never past t_limit.
  //
  // A system whose witnesses switch definition at known times (a member
  // witness_switch_after(t): the first such time after t, or +∞) has its
  // steps end there, so that no polynomial spans a switch.
  template <class Rhs>
  void do_step(const Rhs& rhs, double t_limit) {
    if constexpr (requires { rhs.system->witness_switch_after(t_double_); })
      t_limit = std::min(t_limit, rhs.system->witness_switch_after(t_double_));
    x_old_ = x_;
    t_old_ = t_;
    x_old_double_ = x_double_;
    t_old_double_ = t_double_;
    evaluate(*rhs.system, rhs.mode, false);
    *rhs.evaluations += static_cast<std::uint64_t>(order_ + 1);
    if (needs_slope_) {
      evaluate(*rhs.system, rhs.mode, true);
      *rhs.evaluations += static_cast<std::uint64_t>(order_ + 1);
    }
    // the radius of convergence from the state's last two coefficients, and
    // from each witness's (a witness may be a function of t alone, such as
    // a moving table, over a state whose series ends: a free fall)
    // each component against the size of its group (core/error_scale_groups.hpp)
    std::array<double, scale_group_count> group_scale;
    group_scale.fill(scale_floor_);
    for (std::size_t i = 0; i < dimension; ++i)
      group_scale[scale_group[i]] =
          std::max(group_scale[scale_group[i]], std::fabs(static_cast<double>(x_old_[i])));
    const double scale = group_scale[0];  // the mechanical state's
    // ρ = min_j min_rows (s_row / |c_j|)^{1/j} = min_j (max_rows |c_j| / s_row)^{−1/j}
    std::array<double, 2> ratio = {0.0, 0.0};  // orders p − 1 and p
    auto bound_by = [&](const Coefficients& c, double row_scale) {
      for (int j = 0; j < 2; ++j)
        ratio[j] = std::max(ratio[j], std::fabs(static_cast<double>(c[order_ - 1 + j])) / row_scale);
    };
    for (std::size_t i = 0; i < dimension; ++i)
      bound_by(state_coefficients(i), group_scale[scale_group[i]]);
    for (int k = 0; k < output_count_; ++k) {
      const Coefficients w = output_coefficients(k);
      // (the mechanical state's scale, or the witness's own size where larger: a
      // witness whose higher coefficients are the state's, such as a gap,
      // does not shorten the step)
      bound_by(w, std::max({scale, std::fabs(static_cast<double>(w[0])),
                            std::fabs(static_cast<double>(w[1]))}));
    }
    // ρ = exp(−max_j ln(ratio_j) / j): two logarithms and one exponential
    // instead of two powers
    double log_growth = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < 2; ++j)
      if (ratio[j] > 0.0) log_growth = std::max(log_growth, std::log(ratio[j]) / (order_ - 1 + j));
    const double radius = std::exp(-log_growth);
    double h = radius * safety_;
    const double room = t_limit - t_old_double_;
    if (!std::isfinite(h)) h = room;  // a polynomial solution: exact at any step
    if (!(h > 0.0)) throw std::runtime_error("taylor: step size underflow");
    if (h >= room) {
      t_double_ = t_limit;
      t_ = t_limit;
    } else {
      t_ = t_old_ + Real(h);
      t_double_ = static_cast<double>(t_);
    }
    step_ = t_ - t_old_;
    evaluate_state(step_, x_);
    for (std::size_t i = 0; i < dimension; ++i) x_double_[i] = static_cast<double>(x_[i]);
  }

  template <class Rhs>
  void state_at(const Rhs&, double t, State& x) const {
    if (t == t_double_) {
      x = x_double_;
      return;
    }
    RealState xr;
    evaluate_state(Real(t) - t_old_, xr);
    for (std::size_t i = 0; i < dimension; ++i) x[i] = static_cast<double>(xr[i]);
  }
  template <class Rhs>
  void polish_state(const Rhs& rhs, double t, State& x) const { state_at(rhs, t, x); }
  template <class Rhs>
  void scan_state(const Rhs& rhs, double t, State& x) const { state_at(rhs, t, x); }

  [[nodiscard]] double previous_time() const { return t_old_double_; }
  [[nodiscard]] double current_time() const { return t_double_; }
  [[nodiscard]] const State& current_state() const { return x_double_; }
  [[nodiscard]] const State& previous_state() const { return x_old_double_; }
  [[nodiscard]] double suggested_step() const { return static_cast<double>(step_); }

  // The earliest event of the last step's mode in [ta, tb] ⊂ the last step,
  // on the witnesses' Taylor polynomials (see the header comment). Same
  // contract as integrate/event_location.hpp's locate_first_event.
  [[nodiscard]] LocatedEvent locate_first_event(const System& system, Mode mode, double ta,
                                                double tb, const EventLocationOptions& options,
                                                std::size_t just_grazed) const {
    using std::fabs;
    LocatedEvent best;
    const Real h_end = tb == t_double_ ? step_ : Real(tb) - t_old_;
    const Real h_start = ta == t_old_double_ ? Real(0) : Real(ta) - t_old_;
    const double tolerance = options.grazing_tolerance;
    // H^j of the step's end, shared by the witnesses' exclusion tests (over
    // [0, H] ⊇ [0, h_limit]: a bound over the longer interval holds over
    // the shorter)
    std::array<Real, taylor_max_order + 1> powers;
    if (h_start == 0) {
      powers[0] = 1;
      for (int j = 1; j <= order_; ++j) powers[j] = powers[j - 1] * h_end;
    }
    for (std::size_t k = 0; k < system.witness_count(mode); ++k) {
      const Coefficients w = output_coefficients(static_cast<int>(k));
      const TriggerDirection direction = system.trigger_direction(mode, k);
      // orientation: the trigger is a fall through zero; an `either` witness
      // is oriented so that its starting side (or the side it leaves zero
      // to) is the armed one
      const Real start_side = at_zero(w[0], w[1], tolerance) ? w[1] : w[0];
      const double s = direction == TriggerDirection::rising   ? -1.0
                       : direction == TriggerDirection::either ? (start_side >= 0 ? 1.0 : -1.0)
                                                               : 1.0;
      const Real h_limit = best.found ? Real(best.t) - t_old_ : h_end;
      if (!(h_limit > h_start)) continue;
      // exclusion: g = s w stays above the tolerance over the whole step, by
      // g(h) >= min(g0, g0 + g1 H) − Σ_{j≥2} |g_j| H^j (the linear part is
      // monotone: its minimum is at an end); most steps end here
      if (h_start == 0 && s * w[0] > tolerance) {
        Real reach = 0;
        for (int j = 2; j <= order_; ++j) reach += fabs(w[j]) * powers[j];
        const Real g0 = s * w[0], linear_end = g0 + (s * w[1]) * h_end;
        if ((linear_end < g0 ? linear_end : g0) - reach > tolerance) continue;
      }
      // filled up to the order; zeros beyond it, which nothing reads (GCC
      // cannot see that, and warned in the rigid pendulum's tangent flows)
      std::array<Real, taylor_max_order + 1> g{};
      for (int j = 0; j <= order_; ++j) g[j] = s * w[j];
      const LocatedEvent candidate =
          first_polynomial_event(g, order_, t_old_, h_start, h_limit, tolerance,
                                 direction != TriggerDirection::either, k == just_grazed, k,
                                 settings_.series_lane);
      if (candidate.found && (!best.found || candidate.t < best.t)) best = candidate;
    }
    return best;
  }

 private:
  // Whether a witness with value v and rate r at the step's start sits at a
  // zero (integrate/event_location.hpp's witness_at_zero: within the
  // grazing tolerance, or within 16 ulps of the start time of one)
  [[nodiscard]] bool at_zero(const Real& v, const Real& r, double tolerance) const {
    return witness_at_zero(v, r, t_old_, tolerance);
  }

  // The right-hand side and the mode's witnesses over a series type, as
  // TaylorSeries runs them (the same for a lone stepper, a batch lane and a
  // pass over lanes).
  struct SeriesRhs {
    const System* system;
    Mode mode;
    template <class Variables, class Time, class Outputs>
    int operator()(const Variables& x, const Time& t, Variables& dxdt, Outputs& witnesses) const {
      system->rhs(mode, x, dxdt, t);
      const auto count = static_cast<int>(system->witness_count(mode));
      if (count > TaylorSeries<Real, dimension>::max_outputs)
        throw std::length_error("taylor: more witnesses than the series holds");
      for (int k = 0; k < count; ++k)
        witnesses[k] = system->witness(mode, static_cast<std::size_t>(k), x, t).value;
      return count;
    }
  };

  // A batch lane's request for this stepper's series (integrate/series_lane.hpp)
  struct LaneRequest : SeriesRequest {
    TaylorStepper* stepper = nullptr;
    const System* system = nullptr;
    Mode mode{};
  };

  // The series of `count` requests of steppers of this type. Each lane's
  // order 0 is recorded on its tape; lanes whose tapes record the same
  // operations at the same order have their orders 1..p computed in one pass
  // over lanes (integrate/series_tape.hpp), up to tape_lane_width at a time;
  // a lane left alone is evaluated in double as evaluate() computes it.
  static void evaluate_requests(SeriesRequest* const* requests, int count) {
    auto evaluate_alone = [](const LaneRequest& request) {
      TaylorStepper& stepper = *request.stepper;
      stepper.series_.evaluate(stepper.x_old_.data(), stepper.t_old_, stepper.order_,
                               SeriesRhs{request.system, request.mode}, false);
      stepper.read_own_series();
    };
    if constexpr (HasTapeRhs<System> && std::is_same_v<Real, double>) {
      if (count == 1) {  // no partner: nothing to record
        evaluate_alone(*static_cast<const LaneRequest*>(requests[0]));
        return;
      }
      for (int i = 0; i < count; ++i) {
        const auto& request = *static_cast<const LaneRequest*>(requests[i]);
        const TaylorStepper& stepper = *request.stepper;
        record_series_tape<dimension>(*request.tape, stepper.x_old_.data(), stepper.t_old_,
                                      SeriesRhs{request.system, request.mode});
      }
      std::array<bool, max_series_lanes> taken{};
      for (int i = 0; i < count; ++i) {
        if (taken[i]) continue;
        auto& first = *static_cast<LaneRequest*>(requests[i]);
        std::array<LaneRequest*, tape_lane_width> members{};
        int n = 0;
        for (int j = i; j < count && n < tape_lane_width; ++j) {
          auto& other = *static_cast<LaneRequest*>(requests[j]);
          if (!taken[j] && one_pass(first, other)) {
            members[n++] = &other;
            taken[j] = true;
          }
        }
        if (n > 1)
          evaluate_pass(members, n);
        else
          evaluate_alone(first);
      }
      return;
    }
    for (int i = 0; i < count; ++i) evaluate_alone(*static_cast<const LaneRequest*>(requests[i]));
  }

  // Whether two recorded requests are one pass over lanes: the same order,
  // and tapes of the same operations
  static bool one_pass(const LaneRequest& a, const LaneRequest& b) {
    return a.stepper->order_ == b.stepper->order_ && a.tape->same_operations(*b.tape);
  }

  // the series of `count` (2..tape_lane_width) recorded requests in one pass
  // over lanes, into rows of the batch's that stay until the lanes' next
  // requests: each stepper reads its coefficients there, not copied into
  // its own rows (6 % fewer instructions on a basins grid, the same time:
  // docs/performance.md); a lane whose signs need their slope takes every
  // row, since evaluating again with the slope reads the rows it leaves
  static void evaluate_pass(const std::array<LaneRequest*, tape_lane_width>& members, int count) {
    std::array<const SeriesTape*, tape_lane_width> tapes{};
    for (int lane = 0; lane < count; ++lane) tapes[lane] = members[lane]->tape;
    SeriesLaneRows& rows = members[0]->row_pool->take();
    replay_series_tapes(tapes, count, members[0]->stepper->order_, rows);
    for (int lane = 0; lane < count; ++lane) {
      TaylorStepper& stepper = *members[lane]->stepper;
      const SeriesTape& tape = *tapes[lane];
      members[lane]->in_pass = true;
      if (Series::lane_needs_slope(rows, tape, lane)) {
        stepper.series_.take_lane(rows, tape, lane, stepper.order_);
        stepper.read_own_series();
        continue;
      }
      stepper.needs_slope_ = false;
      stepper.reads_pass_ = true;
      const int stride = rows.lane_stride();
      for (std::size_t i = 0; i < dimension; ++i)
        stepper.pass_state_[i] = {rows.lane_coefficients(static_cast<int>(i), lane), stride};
      stepper.output_count_ = tape.output_count();
      for (int j = 0; j < tape.output_count(); ++j)
        stepper.pass_outputs_[j] = {rows.lane_coefficients(tape.output_row(j), lane), stride};
    }
  }

  // the coefficients of the state and of the mode's witnesses at the step's
  // start: from the batch lane where the stepper runs in one (without the
  // signs' slope, as a batch evaluates), here otherwise
  void evaluate(const System& system, Mode mode, bool signs_from_slope) {
    if constexpr (std::is_same_v<Real, double>) {
      if (settings_.series_lane != nullptr && !signs_from_slope) {
        LaneRequest request;
        request.evaluate = &evaluate_requests;
        request.stepper = this;
        request.system = &system;
        request.mode = mode;
        settings_.series_lane->compute(request);
        return;
      }
    }
    SeriesRhs rhs{&system, mode};
    series_.evaluate(x_old_.data(), t_old_, order_, rhs, signs_from_slope);
    read_own_series();
  }

  // the coefficients are this stepper's own series'
  void read_own_series() {
    reads_pass_ = false;
    needs_slope_ = series_.needs_slope();
    output_count_ = series_.output_count();
  }

  // One row's coefficients 0..order where they lie: the stepper's own
  // series (stride 1), or its lane of a pass (one coefficient every
  // pass-width doubles).
  struct Coefficients {
    const Real* first = nullptr;
    int stride = 1;
    const Real& operator[](int j) const { return first[static_cast<std::ptrdiff_t>(j) * stride]; }
  };
  [[nodiscard]] Coefficients state_coefficients(std::size_t i) const {
    return reads_pass_ ? pass_state_[i] : Coefficients{series_.state(i), 1};
  }
  [[nodiscard]] Coefficients output_coefficients(int k) const {
    return reads_pass_ ? pass_outputs_[k] : Coefficients{series_.output(k), 1};
  }

  // the polynomial at h (s past the step's start)
  void evaluate_state(const Real& h, RealState& x) const {
    for (std::size_t i = 0; i < dimension; ++i) x[i] = polynomial_at(state_coefficients(i), order_, h);
  }

  static constexpr ErrorScaleGroupsOf<System> scale_group = error_scale_groups_of<System>();
  static constexpr std::size_t scale_group_count = impactlab::error_scale_group_count<System>();
  StepperSettings settings_;
  int order_;
  double safety_;       // h / ρ: e^{−1.3} e^{−0.7 / (p − 1)}
  double scale_floor_;  // atol / rtol (state units)
  using Series = TaylorSeries<Real, dimension>;
  Series series_;
  // where the last step's coefficients are read (read_own_series,
  // evaluate_pass): a pass's rows stay until this stepper's next request
  bool reads_pass_ = false;
  bool needs_slope_ = false;
  int output_count_ = 0;
  std::array<Coefficients, dimension> pass_state_{};
  std::array<Coefficients, Series::max_outputs> pass_outputs_{};
  RealState x_{}, x_old_{};             // the step's end and start
  Real t_ = 0, t_old_ = 0, step_ = 0;   // s
  State x_double_{}, x_old_double_{};   // the same, rounded, as the loop sees them
  double t_double_ = 0.0, t_old_double_ = 0.0;
};

}  // namespace impactlab
