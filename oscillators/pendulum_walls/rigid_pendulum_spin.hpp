// The rigid-body pendulum (rigid_pendulum_walls.hpp) with its spin fixed at
// compile time, for the analyses that need its Jacobians (Floquet
// multipliers, Lyapunov exponents, periodic orbits, continuation):
//   spin locked  tangent space (θ, θ̇)      N = 2
//   spin free    tangent space (θ, θ̇, φ̇)   N = 3
// The ball's angle φ and the friction work are bookkeeping: neither feeds
// back into the motion (core/has_jacobian.hpp).
//
// Nothing here is differentiated by hand. The vector field's Jacobian and
// the witnesses' gradients come from forward-mode automatic differentiation
// (integrate/dual_number.hpp) of the system's own right-hand side and
// witnesses, which are written over a number type. An event's reset is
// differentiated the same way, in (x, t):
//   impact       the rates after the Newton–Coulomb impulse in the case it
//                took (stick, or slide with its slip sign), rates_after_impact;
//   accumulation the impact's reset, then the jump to rest on the wall at
//                the accumulation point t + T with the impact's spin: the
//                state there is read at the reference time, x⁺ − f⁺ T(x, t),
//                T the estimate the event loop takes (contact/accumulation.hpp's
//                accumulation_time);
//   slip stops, stick ends
//                the spin set to roll, φ̇ = w V0 sin ωt / r;
//   release      the ball leaves the wall at rest with the spin it has.
// The saltation matrix is then analysis/saltation.hpp's. A contact phase
// pins θ and θ̇; sticking (rolling) pins the spin too. Where no saltation
// matrix exists, the analyses report a typed termination, never a matrix: a
// Painlevé configuration (the event loop's own stop), and an impulse on the
// friction cone's edge, where the stick and slide cases give the same rates
// but not the same derivatives (the reset is marked one-sided, the run goes
// on, and what would report the linearisation says no_tangent_map).
#pragma once

#include <array>
#include <cstddef>

#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/integrate/dual_number.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>

namespace impactlab {

enum class RigidSpin { locked, free };

template <RigidSpin spin>
class RigidPendulumOf : public RigidPendulumWalls {
 public:
  static constexpr std::size_t tangent_dimension = spin == RigidSpin::free ? 3 : 2;
  using Matrix = TangentMatrixOf<tangent_dimension>;
  using Vector = TangentVectorOf<tangent_dimension>;

  explicit RigidPendulumOf(const RigidPendulumParameters& p)
      : RigidPendulumWalls(with_spin(p)) {}

  // ∂f/∂x on the tangent space
  void jacobian(Mode mode, const State& x, double t, Matrix& j) const {
    std::array<Tangent, 5> dxdt;
    rhs(mode, seeded<Tangent>(x), dxdt, Tangent(t));
    for (std::size_t row = 0; row < tangent_dimension; ++row)
      for (std::size_t column = 0; column < tangent_dimension; ++column)
        j[row][column] = dxdt[row].derivative(column);
  }

  // ∂h/∂x of witness k on the tangent space
  [[nodiscard]] Vector witness_gradient(Mode mode, std::size_t k, const State& x,
                                        double t) const {
    const BasicWitnessSample<Tangent> h = witness(mode, k, seeded<Tangent>(x), Tangent(t));
    Vector gradient;
    for (std::size_t i = 0; i < tangent_dimension; ++i) gradient[i] = h.value.derivative(i);
    return gradient;
  }

  // every contact phase pins the ball on the wall at rest (θ, θ̇); sticking
  // also pins its spin to the rolling rate
  [[nodiscard]] bool pinned(Mode mode) const {
    return mode != Mode::free && (spin == RigidSpin::locked || is_stick(mode));
  }
  // 1 for each tangent component a mode pins, 0 for the free ones
  [[nodiscard]] Vector pinned_components(Mode mode) const {
    Vector mask{};
    if (mode == Mode::free) return mask;
    mask[0] = mask[1] = 1.0;
    if constexpr (spin == RigidSpin::free) mask[2] = is_stick(mode) ? 1.0 : 0.0;
    return mask;
  }

  [[nodiscard]] ResetJacobianOf<tangent_dimension> reset_jacobian(
      Mode mode, std::size_t k, CrossingKind crossing, const State& x, double t,
      const Transition<State, Mode>& after) const {
    if (crossing == CrossingKind::grazing || after.stop) return identity_reset<tangent_dimension>();
    if (is_stick(after.mode)) return collapsed_reset<tangent_dimension>();
    const std::array<TangentAndTime, 5> xd = seeded<TangentAndTime>(x);
    const TangentAndTime td(t, unit<TangentAndTime>(tangent_dimension));
    std::array<TangentAndTime, tangent_dimension> reset;
    bool one_sided = false;
    if (mode == Mode::free) {
      const int wall = k == 0 ? 1 : -1;
      const ImpactCase impact = impact_case(wall, x, t);
      one_sided = impact.on_cone_edge;
      const std::array<TangentAndTime, 2> rates = rates_after_impact(wall, impact, xd, td);
      reset[0] = TangentAndTime(wall * wall_angle());
      reset[1] = rates[0];
      if constexpr (spin == RigidSpin::free) reset[2] = rates[1];
      if (after.time > t) {
        // at rest on the wall with the spin of the impact, read at the
        // reference time
        const TangentAndTime remaining =
            accumulation_time(normal_speed(rates[0]), approach_acceleration(td),
                              approach_acceleration_rate(td), parameters().e_n, normal_damping());
        reset[1] = TangentAndTime(0.0);
        State f_after;
        rhs(after.mode, after.state, f_after, after.time);
        for (std::size_t i = 0; i < tangent_dimension; ++i)
          reset[i] = reset[i] - f_after[i] * remaining;
      }
    } else {
      const int wall = wall_of(mode);
      reset[0] = TangentAndTime(wall * wall_angle());
      reset[1] = TangentAndTime(0.0);
      if constexpr (spin == RigidSpin::free)
        reset[2] = k == 0 ? xd[spin_rate] : wall * pivot_velocity(td) / radius();
    }
    ResetJacobianOf<tangent_dimension> jacobian;
    for (std::size_t i = 0; i < tangent_dimension; ++i) {
      for (std::size_t j = 0; j < tangent_dimension; ++j)
        jacobian.state[i][j] = reset[i].derivative(j);
      jacobian.time[i] = reset[i].derivative(tangent_dimension);
    }
    jacobian.one_sided = one_sided;
    return jacobian;
  }

 private:
  using Tangent = Dual<double, tangent_dimension>;
  // the tangent directions and the time's
  using TangentAndTime = Dual<double, tangent_dimension + 1>;

  static RigidPendulumParameters with_spin(RigidPendulumParameters p) {
    p.spin_free = spin == RigidSpin::free;
    return p;
  }
  // the state as dual numbers of D, the tangent components seeded with
  // their own directions (D's further direction, the time's, left zero)
  template <class D>
  static typename D::Derivatives unit(std::size_t direction) {
    typename D::Derivatives e{};
    e[direction] = 1.0;
    return e;
  }
  template <class D>
  static std::array<D, 5> seeded(const State& x) {
    std::array<D, 5> xd;
    for (std::size_t i = 0; i < 5; ++i) xd[i] = i < tangent_dimension ? D(x[i], unit<D>(i)) : D(x[i]);
    return xd;
  }
};

using LockedSpinPendulum = RigidPendulumOf<RigidSpin::locked>;
using FreeSpinPendulum = RigidPendulumOf<RigidSpin::free>;

static_assert(HasJacobian<LockedSpinPendulum>);
static_assert(HasJacobian<FreeSpinPendulum>);
static_assert(HasSeriesRhs<FreeSpinPendulum>);

}  // namespace impactlab
