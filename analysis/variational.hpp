// The variational equations of a hybrid system as a hybrid system itself, so
// that the one event loop (core/simulator.hpp) integrates them unchanged.
//
// State: the base system's state, then Φ, the 2 × 2 fundamental matrix on the
// tangent space (q, q̇), row-major. Between events Φ' = J(x, t) Φ with J the
// mode's Jacobian; at an event Φ⁺ = S Φ⁻ with S the saltation matrix
// (analysis/saltation.hpp) of the base system's transition. Starting from
// Φ = I at t0, Φ at t is the Jacobian of the event-driven flow from t0 to t.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <tuple>

#include "analysis/saltation.hpp"
#include "core/has_jacobian.hpp"

namespace impactlab {

template <HasJacobian Base>
class Variational {
 public:
  using BaseState = typename Base::State;
  using Mode = typename Base::Mode;
  static constexpr std::size_t base_size = std::tuple_size_v<BaseState>;
  static constexpr std::size_t matrix_size = tangent_dimension * tangent_dimension;
  using State = std::array<double, base_size + matrix_size>;
  static constexpr std::size_t max_witnesses = Base::max_witnesses;

  explicit Variational(const Base& base) : base_(base) {}

  [[nodiscard]] const Base& base() const { return base_; }

  // The base state with Φ = I appended (Φ = 0 in a mode that pins the state:
  // there nearby states are the same state).
  State start(const BaseState& x, Mode mode) const {
    State v{};
    std::copy(x.begin(), x.end(), v.begin());
    const double identity = base_.pinned(mode) ? 0.0 : 1.0;
    v[base_size] = identity;
    v[base_size + 3] = identity;
    return v;
  }
  static BaseState base_state(const State& v) {
    BaseState x;
    std::copy_n(v.begin(), base_size, x.begin());
    return x;
  }
  static TangentMatrix fundamental_matrix(const State& v) {
    return {{{v[base_size], v[base_size + 1]}, {v[base_size + 2], v[base_size + 3]}}};
  }

  [[nodiscard]] double max_step() const { return base_.max_step(); }

  void rhs(Mode mode, const State& v, State& dvdt, double t) const {
    const BaseState x = base_state(v);
    BaseState dxdt;
    base_.rhs(mode, x, dxdt, t);
    std::copy(dxdt.begin(), dxdt.end(), dvdt.begin());
    TangentMatrix j;
    base_.jacobian(mode, x, t, j);
    const TangentMatrix phi = fundamental_matrix(v);
    const TangentMatrix rate = multiply(j, phi);
    dvdt[base_size] = rate[0][0];
    dvdt[base_size + 1] = rate[0][1];
    dvdt[base_size + 2] = rate[1][0];
    dvdt[base_size + 3] = rate[1][1];
  }

  [[nodiscard]] std::size_t witness_count(Mode mode) const { return base_.witness_count(mode); }
  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    return base_.trigger_direction(mode, k);
  }
  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& v, double t) const {
    return base_.witness(mode, k, base_state(v), t);
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing,
                                   const State& v, double t, EventLog& log) const {
    const BaseState x = base_state(v);
    const auto after = base_.on_event(mode, k, crossing, x, t, log);
    const TangentMatrix phi =
        multiply(saltation_matrix(base_, mode, k, crossing, x, t, after), fundamental_matrix(v));
    return {with_matrix(after.state, phi), after.mode, after.time, after.stop};
  }

  // For a base whose exact flow is affine in the initial state, the flow's
  // Jacobian is the difference of two flows: column i is
  // flow(x0 + e_i) − flow(x0), exact whatever the size of e_i.
  void exact_flow(Mode mode, const State& v0, double t0, double t, State& v) const
    requires HasExactFlow<Base> && Base::affine_flow
  {
    const BaseState x0 = base_state(v0);
    BaseState x, shifted_q = x0, shifted_qdot = x0, moved_q, moved_qdot;
    shifted_q[0] += 1.0;
    shifted_qdot[1] += 1.0;
    base_.exact_flow(mode, x0, t0, t, x);
    base_.exact_flow(mode, shifted_q, t0, t, moved_q);
    base_.exact_flow(mode, shifted_qdot, t0, t, moved_qdot);
    const TangentMatrix flow_jacobian{{{moved_q[0] - x[0], moved_qdot[0] - x[0]},
                                       {moved_q[1] - x[1], moved_qdot[1] - x[1]}}};
    v = with_matrix(x, multiply(flow_jacobian, fundamental_matrix(v0)));
  }

 private:
  static State with_matrix(const BaseState& x, const TangentMatrix& phi) {
    State v{};
    std::copy(x.begin(), x.end(), v.begin());
    v[base_size] = phi[0][0];
    v[base_size + 1] = phi[0][1];
    v[base_size + 2] = phi[1][0];
    v[base_size + 3] = phi[1][1];
    return v;
  }

  Base base_;
};

}  // namespace impactlab
