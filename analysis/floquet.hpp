// Periodic orbits of the forced systems and their stability: the Jacobian of
// the event-driven flow over a time span (the variational equations with
// saltation matrices, analysis/variational.hpp), Newton shooting on the
// stroboscopic Poincaré map with that monodromy matrix, Floquet multipliers,
// and the largest Lyapunov exponent from the same tangent dynamics.
//
// A period-n orbit of a system forced with period T is a fixed point of the
// n-th iterate of the stroboscopic map P: x(t0) ↦ x(t0 + nT). Its monodromy
// matrix M = ∂Pⁿ/∂x on (q, q̇); the eigenvalues of M are the Floquet
// multipliers: a multiplier through −1 is a period doubling, through +1 a fold.
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>

#include "analysis/flow_setup.hpp"
#include "analysis/variational.hpp"
#include "core/simulator.hpp"
#include "integrate/stepper_dispatch.hpp"

namespace impactlab {

template <class State, class Mode>
struct FlowWithJacobian {
  State state{};             // the base system's state at t
  Mode mode{};               // and its mode
  TangentMatrix jacobian{};  // ∂x(t)/∂x(t0) on (q, q̇)
  Termination termination = Termination::completed;
  std::uint64_t impacts = 0;
};

// The flow from (t0, x0) to t1 and its Jacobian.
template <HasJacobian System>
FlowWithJacobian<typename System::State, typename System::Mode> flow_with_jacobian(
    const System& system, const FlowSetup& setup, const typename System::State& x0,
    typename System::Mode mode, double t0, double t1) {
  using Tangent = Variational<System>;
  const Tangent tangent(system);
  EventLog log(false);
  const auto run = with_stepper<Tangent>(
      setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
        return simulate(tangent, stepper, tangent.start(x0, mode), mode, t0, t1, loop_options(setup),
                        log);
      });
  return {Tangent::base_state(run.state), run.mode, Tangent::fundamental_matrix(run.state),
          run.termination, log.count(EventKind::impact)};
}

// Eigenvalues of a 2 × 2 matrix, largest modulus first.
inline std::array<std::complex<double>, 2> eigenvalues(const TangentMatrix& m) {
  const double half_trace = 0.5 * (m[0][0] + m[1][1]);
  const double determinant = m[0][0] * m[1][1] - m[0][1] * m[1][0];
  const std::complex<double> root = std::sqrt(std::complex<double>(half_trace * half_trace - determinant));
  std::complex<double> a = half_trace + root, b = half_trace - root;
  if (std::abs(b) > std::abs(a)) std::swap(a, b);
  return {a, b};
}

template <class State, class Mode>
struct PeriodicOrbit {
  State state{};               // a point of the orbit on the section t0 (mod nT)
  Mode mode{};
  TangentMatrix monodromy{};   // ∂Pⁿ/∂x on (q, q̇)
  std::array<std::complex<double>, 2> multipliers{};  // eigenvalues of M, largest modulus first
  bool converged = false;
  int iterations = 0;
  double residual = std::numeric_limits<double>::quiet_NaN();  // |Pⁿ(x) − x| on (q, q̇)
  Termination termination = Termination::completed;
};

// Newton's method on Pⁿ(x) − x = 0 over (q, q̇), with (M − I) δ = −(Pⁿ(x) − x),
// from `guess` on the section t0; span = nT (s). A step that makes the
// residual grow, or leaves the admissible states (the run stops), is halved,
// up to 20 times. Stops when the residual is below tolerance × (1 + |x|), or
// after max_iterations.
template <HasJacobian System>
PeriodicOrbit<typename System::State, typename System::Mode> locate_periodic_orbit(
    const System& system, const FlowSetup& setup, typename System::State guess,
    typename System::Mode mode, double t0, double span, int max_iterations = 30,
    double tolerance = 1e-11) {
  using State = typename System::State;
  PeriodicOrbit<State, typename System::Mode> orbit;
  orbit.state = guess;
  orbit.mode = mode;
  auto residual_of = [](const State& x, const State& image) {
    return std::hypot(image[0] - x[0], image[1] - x[1]);
  };
  auto image = flow_with_jacobian(system, setup, orbit.state, orbit.mode, t0, t0 + span);
  orbit.termination = image.termination;
  for (int iteration = 0;; ++iteration) {
    orbit.monodromy = image.jacobian;
    orbit.iterations = iteration;
    orbit.residual = residual_of(orbit.state, image.state);
    if (image.termination != Termination::completed) break;
    if (orbit.residual <= tolerance * (1.0 + std::hypot(orbit.state[0], orbit.state[1]))) {
      orbit.converged = true;
      break;
    }
    if (iteration == max_iterations) break;
    // (M − I) δ = −r by Cramer's rule (2 × 2)
    const double r0 = image.state[0] - orbit.state[0];
    const double r1 = image.state[1] - orbit.state[1];
    const double a = orbit.monodromy[0][0] - 1.0, b = orbit.monodromy[0][1];
    const double c = orbit.monodromy[1][0], d = orbit.monodromy[1][1] - 1.0;
    const double determinant = a * d - b * c;
    if (determinant == 0.0 || !std::isfinite(determinant)) break;
    const double step_q = (-r0 * d + r1 * b) / determinant;
    const double step_qdot = (-a * r1 + c * r0) / determinant;
    bool accepted = false;
    for (double fraction = 1.0; fraction > 1e-6 && !accepted; fraction *= 0.5) {
      State trial = orbit.state;
      trial[0] += fraction * step_q;
      trial[1] += fraction * step_qdot;
      auto trial_image = flow_with_jacobian(system, setup, trial, orbit.mode, t0, t0 + span);
      if (trial_image.termination == Termination::completed &&
          residual_of(trial, trial_image.state) < orbit.residual) {
        orbit.state = trial;
        image = trial_image;
        accepted = true;
      }
    }
    if (!accepted) break;
  }
  orbit.multipliers = eigenvalues(orbit.monodromy);
  return orbit;
}

struct LyapunovResult {
  double exponent = std::numeric_limits<double>::quiet_NaN();  // 1/s (per unit time)
  int periods = 0;  // forcing periods averaged over
  Termination termination = Termination::completed;
};

// The largest Lyapunov exponent along the trajectory from (t0, x0): a tangent
// vector is carried through one forcing period at a time by the period's
// Jacobian (saltation matrices included) and renormalised; the growth of its
// logarithm is averaged over `periods` periods after `alignment_periods`
// periods that let it turn into the most unstable direction. A trajectory
// that merges nearby states (rest on a wall) gives −∞.
template <HasJacobian System>
LyapunovResult largest_lyapunov_exponent(const System& system, const FlowSetup& setup,
                                         typename System::State x, typename System::Mode mode,
                                         double t0, double period, int periods,
                                         int alignment_periods) {
  LyapunovResult result;
  TangentVector v{std::sqrt(0.5), std::sqrt(0.5)};
  double log_growth = 0.0;
  for (int k = 0; k < alignment_periods + periods; ++k) {
    const double ta = t0 + k * period;
    const auto step = flow_with_jacobian(system, setup, x, mode, ta, t0 + (k + 1) * period);
    if (step.termination != Termination::completed) {
      result.termination = step.termination;
      return result;
    }
    x = step.state;
    mode = step.mode;
    const TangentVector w{step.jacobian[0][0] * v[0] + step.jacobian[0][1] * v[1],
                          step.jacobian[1][0] * v[0] + step.jacobian[1][1] * v[1]};
    const double norm = std::hypot(w[0], w[1]);
    if (k >= alignment_periods) log_growth += std::log(norm);
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      result.exponent = norm > 0.0 ? std::numeric_limits<double>::quiet_NaN()
                                   : -std::numeric_limits<double>::infinity();
      result.periods = k + 1 - alignment_periods;
      return result;
    }
    v = {w[0] / norm, w[1] / norm};
  }
  result.periods = periods;
  result.exponent = log_growth / (periods * period);
  return result;
}

}  // namespace impactlab
