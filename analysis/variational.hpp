// The variational equations of a hybrid system as a hybrid system itself, so
// that the one event loop (simulate/simulator.hpp) integrates them unchanged.
//
// State: the base system's state, then Φ, the N × N fundamental matrix on the
// base's tangent space (core/has_jacobian.hpp: (q, q̇), or a model file's N
// states), row-major. Between events Φ' = J(x, t) Φ with J the
// mode's Jacobian; at an event Φ⁺ = S Φ⁻ with S the saltation matrix
// (analysis/saltation.hpp) of the base system's transition. Starting from
// Φ = I at t0, Φ at t is the Jacobian of the event-driven flow from t0 to t.
//
// Where the base's right-hand side and witnesses are written over a number
// type, so are these (Φ' by forward-mode differentiation of the base's rhs),
// and the Taylor stepper integrates the variational equations too.
#pragma once

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <tuple>

#include <impactlab/analysis/saltation.hpp>
#include <impactlab/core/error_scale_groups.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/integrate/dual_number.hpp>

namespace impactlab {

template <HasJacobian Base>
class Variational {
 public:
  using BaseState = typename Base::State;
  using Mode = typename Base::Mode;
  static constexpr std::size_t base_size = std::tuple_size_v<BaseState>;
  static constexpr std::size_t dimension = tangent_dimension_of<Base>;  // N
  using Matrix = TangentMatrixOf<dimension>;
  static constexpr std::size_t matrix_size = dimension * dimension;
  using State = std::array<double, base_size + matrix_size>;
  static constexpr std::size_t max_witnesses = Base::max_witnesses;
  // the base's error scale groups, then Φ as one group of its own
  // (core/error_scale_groups.hpp): the tangent vectors grow by the flow's
  // stretching, and their size says nothing about the accuracy the base
  // state needs
  static constexpr std::array<std::size_t, base_size + matrix_size> error_scale_groups = [] {
    std::array<std::size_t, base_size + matrix_size> groups{};
    const auto base_groups = error_scale_groups_of<Base>();
    std::copy(base_groups.begin(), base_groups.end(), groups.begin());
    std::fill(groups.begin() + base_size, groups.end(), error_scale_group_count<Base>());
    return groups;
  }();

  explicit Variational(const Base& base) : base_(base) {}

  [[nodiscard]] const Base& base() const { return base_; }

  // The base state with Φ = I appended (Φ = 0 in a mode that pins the state:
  // there nearby states are the same state; zero rows for the components a
  // mode pins where the base tells them apart, pinned_components).
  State start(const BaseState& x, Mode mode) const {
    State v{};
    std::copy(x.begin(), x.end(), v.begin());
    TangentVectorOf<dimension> pinned{};
    if constexpr (requires { base_.pinned_components(mode); })
      pinned = base_.pinned_components(mode);
    else if (base_.pinned(mode))
      pinned.fill(1.0);
    for (std::size_t i = 0; i < dimension; ++i)
      v[base_size + i * dimension + i] = pinned[i] != 0.0 ? 0.0 : 1.0;
    return v;
  }
  static BaseState base_state(const State& v) {
    BaseState x;
    std::copy_n(v.begin(), base_size, x.begin());
    return x;
  }
  static Matrix fundamental_matrix(const State& v) {
    Matrix phi;
    for (std::size_t i = 0; i < dimension; ++i)
      for (std::size_t j = 0; j < dimension; ++j) phi[i][j] = v[base_size + i * dimension + j];
    return phi;
  }

  [[nodiscard]] double max_step() const { return base_.max_step(); }
  // the base's switch times (integrate/taylor_stepper.hpp's do_step), where
  // it has them
  [[nodiscard]] double witness_switch_after(double t) const
    requires requires(const Base& base, double time) { base.witness_switch_after(time); }
  {
    return base_.witness_switch_after(t);
  }

  void rhs(Mode mode, const State& v, State& dvdt, double t) const {
    const BaseState x = base_state(v);
    BaseState dxdt;
    base_.rhs(mode, x, dxdt, t);
    std::copy(dxdt.begin(), dxdt.end(), dvdt.begin());
    Matrix j;
    base_.jacobian(mode, x, t, j);
    put_matrix(multiply(j, fundamental_matrix(v)), dvdt);
  }

  // Over another number type (the Taylor stepper's series type), where the
  // base's right-hand side is written over one: column c of Φ' = J Φ is the
  // derivative of the base's f along column c of Φ, by forward-mode
  // differentiation (integrate/dual_number.hpp) of the base's own rhs on
  // x + Σ_c ε_c Φ_{·c}: one run of the base's rhs with N directions, the
  // tangent components' direction c being their entries of column c (the
  // other components and t have no ε part). The base part of dvdt is the
  // value, so f and what it shares with its derivatives (sin θ, the
  // products) are computed once, not once per column. This is the base's
  // `jacobian` times Φ wherever that Jacobian is ∂f/∂x, which
  // tests/variational_taylor_test.cpp checks; the double path above keeps
  // the base's Jacobian.
  template <class Number>
  void rhs(Mode mode, const std::array<Number, base_size + matrix_size>& v,
           std::array<Number, base_size + matrix_size>& dvdt, const Number& t) const
    requires(!std::same_as<Number, double>) &&
            requires(const Base& base, const std::array<Dual<Number, dimension>, base_size>& x,
                     std::array<Dual<Number, dimension>, base_size>& dxdt,
                     const Dual<Number, dimension>& time) { base.rhs(mode, x, dxdt, time); }
  {
    using Tangent = Dual<Number, dimension>;
    std::array<Tangent, base_size> x, dxdt;
    for (std::size_t i = 0; i < base_size; ++i) {
      if (i < dimension) {
        // row i of Φ: component i's derivative along each column
        typename Tangent::Derivatives phi_row;
        std::copy_n(v.begin() + base_size + i * dimension, dimension, phi_row.begin());
        x[i] = Tangent(v[i], phi_row);
      } else {
        x[i] = Tangent(v[i]);
      }
    }
    base_.rhs(mode, x, dxdt, Tangent(t));
    for (std::size_t i = 0; i < base_size; ++i) dvdt[i] = dxdt[i].value();
    for (std::size_t i = 0; i < dimension; ++i)
      std::copy(dxdt[i].derivatives().begin(), dxdt[i].derivatives().end(),
                dvdt.begin() + base_size + i * dimension);
  }

  [[nodiscard]] std::size_t witness_count(Mode mode) const { return base_.witness_count(mode); }
  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    return base_.trigger_direction(mode, k);
  }
  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& v, double t) const {
    return base_.witness(mode, k, base_state(v), t);
  }
  // over another number type: the base's witness of the base part
  template <class Number>
  [[nodiscard]] auto witness(Mode mode, std::size_t k,
                             const std::array<Number, base_size + matrix_size>& v,
                             const Number& t) const
    requires(!std::same_as<Number, double>) &&
            requires(const Base& base, const std::array<Number, base_size>& x) {
              base.witness(mode, k, x, t);
            }
  {
    std::array<Number, base_size> x;
    std::copy_n(v.begin(), base_size, x.begin());
    return base_.witness(mode, k, x, t);
  }

  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing,
                                   const State& v, double t, EventLog& log) const {
    const BaseState x = base_state(v);
    const auto after = base_.on_event(mode, k, crossing, x, t, log);
    const auto saltation = saltation_matrix(base_, mode, k, crossing, x, t, after);
    const Matrix phi = multiply(saltation.matrix, fundamental_matrix(v));
    return {with_matrix(after.state, phi), after.mode, after.time, after.stop,
            saltation.one_sided || after.one_sided};
  }

  // For a base whose exact flow is affine in the initial state, the flow's
  // Jacobian is the difference of two flows: column i is
  // flow(x0 + e_i) − flow(x0), exact whatever the size of e_i.
  void exact_flow(Mode mode, const State& v0, double t0, double t, State& v) const
    requires HasExactFlow<Base> && requires { requires Base::affine_flow; }
  {
    const BaseState x0 = base_state(v0);
    BaseState x;
    base_.exact_flow(mode, x0, t0, t, x);
    Matrix flow_jacobian;
    for (std::size_t column = 0; column < dimension; ++column) {
      BaseState shifted = x0, moved;
      shifted[column] += 1.0;
      base_.exact_flow(mode, shifted, t0, t, moved);
      for (std::size_t row = 0; row < dimension; ++row)
        flow_jacobian[row][column] = moved[row] - x[row];
    }
    v = with_matrix(x, multiply(flow_jacobian, fundamental_matrix(v0)));
  }

 private:
  static void put_matrix(const Matrix& phi, State& v) {
    for (std::size_t i = 0; i < dimension; ++i)
      for (std::size_t j = 0; j < dimension; ++j) v[base_size + i * dimension + j] = phi[i][j];
  }
  static State with_matrix(const BaseState& x, const Matrix& phi) {
    State v{};
    std::copy(x.begin(), x.end(), v.begin());
    put_matrix(phi, v);
    return v;
  }

  Base base_;
};

}  // namespace impactlab
