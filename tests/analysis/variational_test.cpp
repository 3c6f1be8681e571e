// Variational (analysis/variational.hpp): every optional hook of the
// hybrid-system concept (core/hybrid_system.hpp, core/has_jacobian.hpp, the
// Taylor stepper's) is forwarded from its base, or deliberately not, for the
// reason stated with its check. The analyses run the variational equations
// in place of the plain system wherever they need a Jacobian (Floquet,
// Lyapunov, continuation), so a hook lost here would quietly change which
// stepper or which path they take.
#include <array>
#include <cstddef>

#include <gtest/gtest.h>

#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/core/hybrid_system.hpp>
#include <impactlab/integrate/taylor_stepper.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::BouncingBall;
using impactlab::DecoratedSystem;
using impactlab::LinearImpact;
using impactlab::PendulumWalls;
using impactlab::Variational;

// A system with Jacobians and a closed-form flow that is not affine in the
// state (ẋ = 1 with q̇ = x², flowed exactly): no built-in oscillator has one.
struct NonAffineExactFlow {
  using State = std::array<double, 2>;
  enum class Mode { free };
  static constexpr std::size_t max_witnesses = 1;
  void rhs(Mode, const State& x, State& dxdt, double) const { dxdt = {x[1], 0.0}; }
  [[nodiscard]] std::size_t witness_count(Mode) const { return 0; }
  [[nodiscard]] impactlab::WitnessSample witness(Mode, std::size_t, const State&, double) const {
    return {};
  }
  [[nodiscard]] impactlab::TriggerDirection trigger_direction(Mode, std::size_t) const {
    return impactlab::TriggerDirection::falling;
  }
  impactlab::Transition<State, Mode> on_event(Mode mode, std::size_t, impactlab::CrossingKind,
                                              const State& x, double t,
                                              impactlab::EventLog&) const {
    return {x, mode, t, false};
  }
  [[nodiscard]] double max_step() const { return 0.1; }
  void exact_flow(Mode, const State& x0, double t0, double t, State& x) const {
    x = {x0[0] + x0[1] * x0[1] * (t - t0), x0[1]};
  }
  void jacobian(Mode, const State&, double, impactlab::TangentMatrix& j) const {
    j = {{{0.0, 1.0}, {0.0, 0.0}}};
  }
  [[nodiscard]] impactlab::TangentVector witness_gradient(Mode, std::size_t, const State&,
                                                          double) const {
    return {};
  }
  [[nodiscard]] impactlab::ResetJacobian reset_jacobian(
      Mode, std::size_t, impactlab::CrossingKind, const State&, double,
      const impactlab::Transition<State, Mode>&) const {
    return impactlab::identity_reset();
  }
  [[nodiscard]] bool pinned(Mode) const { return false; }
};
static_assert(impactlab::HasJacobian<NonAffineExactFlow>);
static_assert(impactlab::HasExactFlow<NonAffineExactFlow>);

template <class Base>
constexpr bool has_switch_times() {
  return requires(const Base& base) { base.witness_switch_after(0.0); };
}

template <class Base>
constexpr bool forwards_or_states_why() {
  using Tangent = Variational<Base>;
  // the variational equations are a hybrid system themselves: the one event
  // loop runs them, and max_step is the base's (checked below by value)
  static_assert(impactlab::HybridSystem<Tangent>);
  // forwarded: Φ' by forward-mode differentiation of the base's series rhs,
  // so the Taylor stepper runs the variational equations where it runs the base
  static_assert(impactlab::HasSeriesRhs<Tangent> == impactlab::HasSeriesRhs<Base>);
  // forwarded: the switch times of the base's witnesses end the Taylor steps
  static_assert(has_switch_times<Tangent>() == has_switch_times<Base>());
  // forwarded only for an affine flow: Φ is then carried by the difference of
  // two flows of the base, exact whatever their size; a flow that is not
  // affine would need its derivative, which the base does not give
  static_assert(impactlab::HasExactFlow<Tangent> ==
                (impactlab::HasExactFlow<Base> && impactlab::affine_flow_of<Base>()));
  // deliberately not: the Jacobians of the variational equations (their own
  // variational equations, second derivatives of the base) are never run, so
  // a Variational has no jacobian, witness_gradient, reset_jacobian, pinned
  // or tangent_dimension, and states no affine_flow: nothing linearises it
  static_assert(!impactlab::HasJacobian<Tangent>);
  static_assert(!impactlab::affine_flow_of<Tangent>());
  return true;
}
static_assert(forwards_or_states_why<PendulumWalls>());
static_assert(forwards_or_states_why<LinearImpact>());
static_assert(forwards_or_states_why<BouncingBall>());
static_assert(forwards_or_states_why<NonAffineExactFlow>());
static_assert(forwards_or_states_why<DecoratedSystem<PendulumWalls>>());
static_assert(forwards_or_states_why<DecoratedSystem<LinearImpact>>());

// the cases above cover both sides of each forwarded hook
static_assert(impactlab::HasSeriesRhs<Variational<LinearImpact>>);
static_assert(!impactlab::HasSeriesRhs<Variational<NonAffineExactFlow>>);
static_assert(has_switch_times<Variational<DecoratedSystem<LinearImpact>>>());
static_assert(!has_switch_times<Variational<LinearImpact>>());
static_assert(impactlab::HasExactFlow<Variational<LinearImpact>>);
static_assert(!impactlab::HasExactFlow<Variational<NonAffineExactFlow>>);
static_assert(!impactlab::HasExactFlow<Variational<PendulumWalls>>);

TEST(Variational, ForwardsTheBaseValuesOfItsHooks) {
  const LinearImpact system(impactlab::LinearImpactParameters{});
  DecoratedSystem<LinearImpact> decorated(system);
  decorated.with_suppressed_contacts(LinearImpact::Mode::free,
                                     impactlab::ContactWindow{0, 1.0, 2.0}, nullptr);
  const Variational<DecoratedSystem<LinearImpact>> tangent(decorated);
  EXPECT_EQ(tangent.max_step(), system.max_step());
  EXPECT_EQ(tangent.witness_switch_after(0.5), 1.0);
  EXPECT_EQ(tangent.witness_switch_after(1.5), 2.0);
  EXPECT_EQ(tangent.witness_switch_after(2.5), decorated.witness_switch_after(2.5));
}

// The exact flow of an affine base carries Φ exactly: Φ(t) = ∂x(t)/∂x(t0),
// column by column the difference of two flows, here against a central
// difference of the base's own flow (affine: exact to round-off).
TEST(Variational, ExactFlowOfAnAffineBaseCarriesItsJacobian) {
  const LinearImpact system(impactlab::LinearImpactParameters{});
  const Variational<LinearImpact> tangent(system);
  const LinearImpact::State x0{0.3, -0.2};
  const double t1 = 0.7;
  Variational<LinearImpact>::State v{};
  tangent.exact_flow(LinearImpact::Mode::free, tangent.start(x0, LinearImpact::Mode::free), 0.0,
                     t1, v);
  const auto phi = Variational<LinearImpact>::fundamental_matrix(v);
  for (std::size_t column = 0; column < 2; ++column) {
    LinearImpact::State up = x0, down = x0, x_up{}, x_down{};
    up[column] += 1e-3;
    down[column] -= 1e-3;
    system.exact_flow(LinearImpact::Mode::free, up, 0.0, t1, x_up);
    system.exact_flow(LinearImpact::Mode::free, down, 0.0, t1, x_down);
    for (std::size_t row = 0; row < 2; ++row)
      EXPECT_NEAR(phi[row][column], (x_up[row] - x_down[row]) / 2e-3, 1e-9);
  }
}

}  // namespace
