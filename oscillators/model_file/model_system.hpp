// A model section's hybrid system (core/hybrid_system.hpp): the compiled
// functions of oscillators/model_file/compiled_model.hpp behind the same
// interface as a hand-written oscillator, so that the event loop, sections,
// sweeps, saltation, Floquet, Lyapunov and continuation run it unchanged.
//
// N, the number of states, is fixed at compile time so that the state is a
// std::array and the loop allocates nothing; the binding instantiates N = 2
// and N = 4. The tangent space of the analyses is all N states. Modes: free flight, and one sticking mode per wall that has one.
// Events per wall k:
//   free flight, the witness h_k crosses zero in its direction: an impact,
//     x⁺ from the wall's reset; with a sticking mode, the impacts that follow
//     are summed into their accumulation point (contact/accumulation.hpp) when
//     the push F into the wall is nearly constant over them (with the gap's
//     damping and stiffness, derived symbolically, in the estimate), and the state
//     rests on the wall (the sticking state) while F > 0;
//   resting on wall k, F falls through zero: release into free flight from
//     the sticking state.
// events.csv's q and qdot are the first two states.
// The right-hand sides and witnesses run over doubles as the compiled
// functions, and over any other number type (the Taylor stepper's series)
// as the model's series programs (series_program.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <vector>

#include <impactlab/contact/accumulation.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>

namespace impactlab {

// 0: free flight; 1 + k: resting on wall k.
enum class ModelMode : std::uint8_t {};

// A model system's parameter values and the forcing frequency they give: the
// analyses read a system's forcing frequency as parameters().omega, as for
// the built-in oscillators' parameter structs.
struct ModelParameterView {
  const std::vector<double>& values;  // in the model's order
  double omega;                       // forcing frequency (rad per time unit)
};

template <std::size_t N>
class ModelSystem {
 public:
  using State = std::array<double, N>;
  using Mode = ModelMode;
  static constexpr std::size_t max_witnesses = 6;
  static constexpr std::size_t tangent_dimension = N;  // core/has_jacobian.hpp: every state
  static constexpr Mode free_mode{0};
  // the model file's names of its states, in its order
  [[nodiscard]] std::vector<std::string_view> state_names() const {
    return {model_->states.begin(), model_->states.end()};
  }

  // parameters: values in the model's order; accumulation: what an
  // accumulation estimate is held to, with the gap's resolution per unit of
  // the wall coordinate (contact/accumulation.hpp; its apex and round-off
  // terms are scaled by the wall coordinate at each impact; a wall's
  // gap_scale raises the round-off to 4 ulps of the terms it names)
  ModelSystem(std::shared_ptr<const CompiledModel> model, std::vector<double> parameters,
              AccumulationTolerance accumulation = {})
      : model_(std::move(model)), p_(std::move(parameters)), accumulation_(accumulation) {
    if (model_->states.size() != N || p_.size() != model_->parameters.size())
      throw std::invalid_argument("ModelSystem: state or parameter count does not match the model");
    double scalars[2];
    model_->scalars(nullptr, 0.0, p_.data(), scalars);
    omega_ = scalars[0];
    max_step_ = scalars[1];
  }

  [[nodiscard]] const CompiledModel& model() const { return *model_; }
  [[nodiscard]] ModelParameterView parameters() const { return {p_, omega_}; }
  [[nodiscard]] double forcing_frequency() const { return omega_; }
  [[nodiscard]] double max_step() const { return max_step_; }
  [[nodiscard]] std::string_view mode_name(Mode mode) const { return model_->mode_names[index(mode)]; }
  static constexpr Mode stuck_mode(std::size_t wall) { return Mode(static_cast<std::uint8_t>(wall + 1)); }

  void rhs(Mode mode, const State& x, State& dxdt, double t) const {
    const std::size_t m = index(mode);
    const Kernel& field = m == 0 ? model_->free_rhs : model_->stick_rhs[m - 1];
    field(x.data(), t, p_.data(), dxdt.data());
  }

  // The right-hand side over a number type other than double: the Taylor
  // stepper's series, the batch's tapes, dual numbers (series_program.hpp).
  // Only for a model without series_refusal: the scene offers no Taylor
  // stepper for the others.
  template <class Number>
  void rhs(Mode mode, const std::array<Number, N>& x, std::array<Number, N>& dxdt,
           const Number& t) const {
    const std::size_t m = index(mode);
    const SeriesProgram& field = m == 0 ? model_->free_rhs_series : model_->stick_rhs_series[m - 1];
    field.run(x.data(), t, p_.data(), dxdt.data());
  }
  [[nodiscard]] std::size_t witness_count(Mode mode) const {
    return index(mode) == 0 ? model_->walls.size() : 1;
  }

  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    return index(mode) == 0 ? model_->walls[k].direction : TriggerDirection::falling;
  }

  // free: the wall's witness and its rate; resting on wall k: the push F, Ḟ
  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& x, double t) const {
    const std::size_t m = index(mode);
    double out[3];
    if (m == 0) {
      model_->gap[k](x.data(), t, p_.data(), out);
    } else {
      model_->stick_force[m - 1](x.data(), t, p_.data(), out);
    }
    return {out[0], out[1]};
  }

  // the same over a number type other than double (rhs, above)
  template <class Number>
  [[nodiscard]] BasicWitnessSample<Number> witness(Mode mode, std::size_t k,
                                                   const std::array<Number, N>& x,
                                                   const Number& t) const {
    const std::size_t m = index(mode);
    const SeriesProgram& witness =
        m == 0 ? model_->gap_series[k] : model_->stick_force_series[m - 1];
    std::array<Number, 2> out;
    witness.run(x.data(), t, p_.data(), out.data());
    return {out[0], out[1]};
  }
  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing, const State& x,
                                   double t, EventLog& log) const {
    const std::size_t m = index(mode);
    if (m == 0) return on_wall_reached(k, crossing, x, t, log);
    // the push only touched zero and stays inward: the state stays on the wall
    if (crossing == CrossingKind::grazing) return {x, mode, t, false};
    const State released = sticking_state(m - 1, x, t);
    log.record({t, EventKind::contact_end, model_->walls[m - 1].side, released[0], released[1],
                released[1]});
    return {released, free_mode, t, false};
  }

  // --- linearisation (core/has_jacobian.hpp) on all N states. A sticking
  // mode pins the whole state, and an accumulation into it collapses nearby
  // states: right for one degree of freedom only (the binding offers no
  // analyses on N > 2 models with sticking walls) ---

  void jacobian(Mode mode, const State& x, double t, TangentMatrixOf<N>& j) const {
    const std::size_t m = index(mode);
    double out[N * N];  // row-major
    const Kernel& field = m == 0 ? model_->free_jacobian : model_->stick_jacobian[m - 1];
    field(x.data(), t, p_.data(), out);
    for (std::size_t row = 0; row < N; ++row) std::copy_n(out + row * N, N, j[row].begin());
  }

  [[nodiscard]] TangentVectorOf<N> witness_gradient(Mode mode, std::size_t k, const State& x,
                                                    double t) const {
    const std::size_t m = index(mode);
    TangentVectorOf<N> g{};
    const Kernel& gradient = m == 0 ? model_->gap_gradient[k] : model_->stick_force_gradient[m - 1];
    gradient(x.data(), t, p_.data(), g.data());
    return g;
  }

  [[nodiscard]] bool pinned(Mode mode) const { return index(mode) != 0; }

  // An impact: ∂x⁺/∂x and ∂x⁺/∂t of the wall's reset, differentiated
  // symbolically. A grazing touch leaves the state alone; an accumulation and
  // a release collapse nearby states into one.
  [[nodiscard]] ResetJacobianOf<N> reset_jacobian(Mode mode, std::size_t k,
                                                  CrossingKind crossing, const State& x, double t,
                                                  const Transition<State, Mode>& after) const {
    if (crossing == CrossingKind::grazing) return identity_reset<N>();
    if (index(mode) != 0 || index(after.mode) != 0 || after.time > t) return collapsed_reset<N>();
    double out[N * N + N];  // ∂x⁺/∂x row-major, then ∂x⁺/∂t
    model_->reset_jacobian[k](x.data(), t, p_.data(), out);
    ResetJacobianOf<N> reset;
    for (std::size_t row = 0; row < N; ++row) std::copy_n(out + row * N, N, reset.state[row].begin());
    std::copy_n(out + N * N, N, reset.time.begin());
    return reset;
  }

 private:
  static constexpr std::size_t index(Mode mode) { return static_cast<std::size_t>(mode); }

  [[nodiscard]] State sticking_state(std::size_t wall, const State& x, double t) const {
    State s;
    model_->stick_state[wall](x.data(), t, p_.data(), s.data());
    return s;
  }

  // An impact (or a grazing touch) on wall k; then flight again, or, when the
  // impacts are accumulating, a jump to their limit and rest on the wall.
  Transition<State, Mode> on_wall_reached(std::size_t k, CrossingKind crossing, const State& x,
                                          double t, EventLog& log) const {
    const CompiledWall& wall = model_->walls[k];
    if (crossing == CrossingKind::grazing) {
      log.record({t, EventKind::grazing, wall.side, x[0], x[1], x[1]});
      return {x, free_mode, t, false};
    }
    double reset[N + 1];  // x⁺, then the restitution
    model_->reset[k](x.data(), t, p_.data(), reset);
    State after;
    std::copy_n(reset, N, after.begin());
    log.record({t, EventKind::impact, wall.side, x[0], x[1], after[1]});
    if (!wall.has_sticking) return {after, free_mode, t, false};

    // chattering: is the wall pushing back, and is the accumulation estimate
    // good? The separation speed is r |ḣ⁻| (Newton's law), not ḣ evaluated
    // after the impact: that difference of nearly equal velocities would lose
    // digits in a chatter, where the speeds are small.
    double gap[2], push[3], chatter[3];
    model_->gap[k](x.data(), t, p_.data(), gap);
    model_->chatter[k](after.data(), t, p_.data(), chatter);  // c, κ, gap_scale
    const State resting = sticking_state(k, after, t);
    model_->stick_force[k](resting.data(), t, p_.data(), push);
    const double restitution = reset[N];
    // the gap's resolution where this wall is: scaled by its coordinate; its
    // round-off at least 4 ulps of the terms the gap is computed from (the
    // wall coordinate and the model's gap_scale), as a built-in oscillator
    // takes its own (linear_impact.hpp: σ and the forced response's amplitude)
    AccumulationTolerance tolerance = accumulation_;
    const double wall_coordinate = std::max(1.0, std::fabs(after[0]));
    tolerance.unresolved_apex *= wall_coordinate;
    tolerance.gap_roundoff =
        std::max(tolerance.gap_roundoff * wall_coordinate,
                 4.0 * std::numeric_limits<double>::epsilon() * (std::fabs(after[0]) + chatter[2]));
    const auto estimate = accept_accumulation(
        {restitution * std::fabs(gap[1]), push[0], push[1], restitution, push[2], chatter[0],
         chatter[1]},
        tolerance);
    if (!estimate) return {after, free_mode, t, false};
    return enter_stuck(k, after, t + estimate->remaining, estimate->error_bound, log);
  }

  // At the accumulation point the state rests on the wall if the push holds it
  // there; otherwise it leaves from the sticking state.
  Transition<State, Mode> enter_stuck(std::size_t k, const State& after, double t,
                                      double time_error, EventLog& log) const {
    const int side = model_->walls[k].side;
    const State resting = sticking_state(k, after, t);
    EventRecord accumulation{t, EventKind::accumulation, side, resting[0], resting[1], resting[1]};
    accumulation.accumulation_error = time_error;
    log.record(accumulation);
    double push[3];
    model_->stick_force[k](resting.data(), t, p_.data(), push);
    if (!(push[0] > 0.0)) return {resting, free_mode, t, false};
    log.record({t, EventKind::contact_start, side, resting[0], resting[1], resting[1]});
    return {resting, stuck_mode(k), t, false};
  }

  std::shared_ptr<const CompiledModel> model_;
  std::vector<double> p_;  // parameter values, in the model's order
  AccumulationTolerance accumulation_;
  double omega_ = 1.0;     // forcing frequency (rad per time unit)
  double max_step_ = 0.1;  // largest integrator step (time)
};

static_assert(HybridSystem<ModelSystem<2>>);
static_assert(HasJacobian<ModelSystem<2>>);
static_assert(HybridSystem<ModelSystem<4>>);
static_assert(HasJacobian<ModelSystem<4>>);

}  // namespace impactlab
