// Periodic orbits of the forced systems and their stability: the Jacobian of
// the event-driven flow over a time span (the variational equations with
// saltation matrices, analysis/variational.hpp), Newton shooting on the
// stroboscopic Poincaré map with that monodromy matrix, Floquet multipliers,
// and the largest Lyapunov exponent from the same tangent dynamics.
//
// A period-n orbit of a system forced with period T is a fixed point of the
// n-th iterate of the stroboscopic map P: x(t0) ↦ x(t0 + nT). Its monodromy
// matrix M = ∂Pⁿ/∂x on the system's N-dimensional tangent space ((q, q̇), or a
// model file's N states); the N eigenvalues of M are the Floquet
// multipliers: a multiplier through −1 is a period doubling, through +1 a fold.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string_view>
#include <optional>

#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/deflation.hpp>
#include <impactlab/analysis/floquet_algebra.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/flow.hpp>

namespace impactlab {

template <class State, class Mode, std::size_t N = default_tangent_dimension>
struct FlowWithJacobian {
  State state{};                  // the base system's state at t
  Mode mode{};                    // and its mode
  TangentMatrixOf<N> jacobian{};  // ∂x(t)/∂x(t0) on the tangent space
  Termination termination = Termination::completed;
  std::uint64_t impacts = 0;
  std::uint64_t contact_phases = 0;  // sustained contacts begun (after an accumulation of impacts)
  bool one_sided = false;  // an event's tangent map on the way is one side's (Transition::one_sided)
};

// The flow from (t0, x0) to t1 and its Jacobian, with a stepper for the
// variational equations `tangent` that the caller holds across calls (one
// from with_flow<Variational<System>>): simulate() initializes it at the
// start of each run, so a Runge–Kutta stepper starts afresh as a new one
// would, and the Taylor stepper keeps its storage.
template <HasJacobian System, class Stepper>
FlowWithJacobian<typename System::State, typename System::Mode, tangent_dimension_of<System>>
flow_with_jacobian(const Variational<System>& tangent, Stepper& stepper, const FlowSetup& setup,
                   const typename System::State& x0, typename System::Mode mode, double t0,
                   double t1) {
  using Tangent = Variational<System>;
  EventLog log(false);
  const auto run =
      simulate(tangent, stepper, tangent.start(x0, mode), mode, t0, t1, loop_options(setup), log);
  return {Tangent::base_state(run.state), run.mode, Tangent::fundamental_matrix(run.state),
          run.termination, log.count(EventKind::impact), log.count(EventKind::contact_start),
          run.counters.one_sided_events > 0};
}

// The tangent dynamics the analyses run for a system: the variational
// equations of the system decorated with nothing switched on (its base,
// number for number, analysis/decorated_system.hpp), one tangent type per
// oscillator shared by Floquet, Lyapunov and continuation.
template <HasJacobian System>
using TangentOf = Variational<DecoratedSystem<System>>;

// The flow from (t0, x0) to t1 and its Jacobian, with a stepper of its own.
template <HasJacobian System>
FlowWithJacobian<typename System::State, typename System::Mode, tangent_dimension_of<System>>
flow_with_jacobian(
    const System& system, const FlowSetup& setup, const typename System::State& x0,
    typename System::Mode mode, double t0, double t1) {
  using Tangent = TangentOf<System>;
  const Tangent tangent{DecoratedSystem<System>(system)};
  return with_flow<Tangent>(
      setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
        return flow_with_jacobian(tangent, stepper, setup, x0, mode, t0, t1);
      });
}

// |v| on the tangent space (std::hypot for N = 2)
template <std::size_t N>
double tangent_norm(const TangentVectorOf<N>& v) {
  if constexpr (N == 2) {
    return std::hypot(v[0], v[1]);
  } else {
    double sum = 0.0;
    for (double component : v) sum += component * component;
    return std::sqrt(sum);
  }
}

// The tangent-space part of a state: its first N components.
template <std::size_t N, class State>
TangentVectorOf<N> tangent_part(const State& x) {
  TangentVectorOf<N> v;
  std::copy_n(x.begin(), N, v.begin());
  return v;
}


template <class State, class Mode, std::size_t N = default_tangent_dimension>
struct PeriodicOrbit {
  State state{};                   // a point of the orbit on the section t0 (mod nT)
  Mode mode{};
  TangentMatrixOf<N> monodromy{};  // ∂Pⁿ/∂x on the tangent space
  std::array<std::complex<double>, N> multipliers{};  // eigenvalues of M, largest modulus first
  bool converged = false;
  int iterations = 0;
  double residual = std::numeric_limits<double>::quiet_NaN();  // |Pⁿ(x) − x| on the tangent space
  Termination termination = Termination::completed;
  std::string_view failure;  // why Newton's method ended unconverged; empty where it converged
};

// Newton's method on Pⁿ(x) − x = 0 over the tangent space's N components,
// with (M − I) δ = −(Pⁿ(x) − x), from `guess` on the section t0; span = nT (s). A step that makes the
// residual grow, or leaves the admissible states (the run stops), is halved,
// up to 20 times. Stops when the residual is below tolerance × (1 + |x|), or
// after max_iterations. An orbit whose map crosses an event with a one-sided
// tangent map (an impulse on the friction cone's edge) ends no_tangent_map,
// its monodromy and multipliers NaN.
// With `deflation` (analysis/deflation.hpp) and its known roots, the step is
// the deflated one and the halving accepts a step that lowers M(x)|Pⁿ(x) − x|
// (the deflated residual); convergence is still judged on |Pⁿ(x) − x|.
// All its flows with the caller's stepper (see flow_with_jacobian above).
template <HasJacobian System, class Stepper>
PeriodicOrbit<typename System::State, typename System::Mode, tangent_dimension_of<System>>
locate_periodic_orbit(const Variational<System>& tangent, Stepper& stepper,
                      const FlowSetup& setup, typename System::State guess,
                      typename System::Mode mode, double t0, double span, int max_iterations,
                      double tolerance, const Deflation* deflation = nullptr) {
  using State = typename System::State;
  constexpr std::size_t n = tangent_dimension_of<System>;
  PeriodicOrbit<State, typename System::Mode, n> orbit;
  orbit.state = guess;
  orbit.mode = mode;
  auto difference = [](const State& x, const State& image) {
    TangentVectorOf<n> r;
    for (std::size_t i = 0; i < n; ++i) r[i] = image[i] - x[i];
    return r;
  };
  auto residual_of = [&](const State& x, const State& image) {
    return tangent_norm<n>(difference(x, image));
  };
  // what a step must lower: |F|, or M |F| where deflating
  auto merit_of = [&](const State& x, double residual) {
    if (deflation == nullptr) return residual;
    const auto point = tangent_part<n>(x);
    return deflation_factor(*deflation, point) * residual;
  };
  auto flow = [&](const State& x) {
    return flow_with_jacobian(tangent, stepper, setup, x, orbit.mode, t0, t0 + span);
  };
  auto image = flow(orbit.state);
  orbit.termination = image.termination;
  for (int iteration = 0;; ++iteration) {
    orbit.monodromy = image.jacobian;
    orbit.iterations = iteration;
    orbit.residual = residual_of(orbit.state, image.state);
    if (image.termination != Termination::completed) {
      orbit.failure = "the run from the iterate stopped early";
      break;
    }
    if (orbit.residual <= tolerance * (1.0 + tangent_norm<n>(tangent_part<n>(orbit.state)))) {
      orbit.converged = true;
      break;
    }
    if (iteration == max_iterations) {
      orbit.failure = "max_iterations reached";
      break;
    }
    auto step = newton_step<n>(orbit.monodromy, difference(orbit.state, image.state));
    if (!step) {
      orbit.failure = "M - I is singular at the iterate (a multiplier at 1): no Newton step";
      break;
    }
    if (deflation != nullptr) {
      const auto point = tangent_part<n>(orbit.state);
      if (!deflate_step(*deflation, point, *step)) {
        orbit.failure = "the deflated Newton step is undefined at the iterate (on a known orbit)";
        break;
      }
    }
    const double merit = merit_of(orbit.state, orbit.residual);
    bool accepted = false;
    for (double fraction = 1.0; fraction > 1e-6 && !accepted; fraction *= 0.5) {
      State trial = orbit.state;
      for (std::size_t i = 0; i < n; ++i) trial[i] += fraction * (*step)[i];
      auto trial_image = flow(trial);
      if (trial_image.termination == Termination::completed &&
          merit_of(trial, residual_of(trial, trial_image.state)) < merit) {
        orbit.state = trial;
        image = trial_image;
        accepted = true;
      }
    }
    if (!accepted) {
      orbit.failure =
          "no step along Newton's direction, halved 20 times, lowers the residual: the start is "
          "too far from an orbit of this period, or the map is not smooth there";
      break;
    }
  }
  if (image.one_sided && orbit.termination == Termination::completed) {
    // the orbit crosses an event with no derivative: Newton's steps may use
    // one side's, but its monodromy and multipliers do not exist
    orbit.termination = Termination::no_tangent_map;
    for (auto& row : orbit.monodromy) row.fill(std::numeric_limits<double>::quiet_NaN());
    orbit.multipliers.fill(std::numeric_limits<double>::quiet_NaN());
    return orbit;
  }
  orbit.multipliers = eigenvalues(orbit.monodromy);
  return orbit;
}

// With one stepper for all the flows of the iteration.
template <HasJacobian System>
PeriodicOrbit<typename System::State, typename System::Mode, tangent_dimension_of<System>>
locate_periodic_orbit(const System& system, const FlowSetup& setup, typename System::State guess,
                      typename System::Mode mode, double t0, double span,
                      int max_iterations = 30, double tolerance = 1e-11,
                      const Deflation* deflation = nullptr) {
  using Tangent = TangentOf<System>;
  const Tangent tangent{DecoratedSystem<System>(system)};
  return with_flow<Tangent>(setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
    return locate_periodic_orbit(tangent, stepper, setup, guess, mode, t0, span, max_iterations,
                                 tolerance, deflation);
  });
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
// that merges nearby states (rest on a wall) gives −∞; one that crosses an
// event with a one-sided tangent map gives NaN and no_tangent_map.
// All its periods with the caller's stepper (see flow_with_jacobian above).
template <HasJacobian System, class Stepper>
LyapunovResult largest_lyapunov_exponent(const Variational<System>& tangent, Stepper& stepper,
                                         const FlowSetup& setup, typename System::State x,
                                         typename System::Mode mode, double t0, double period,
                                         int periods, int alignment_periods) {
  constexpr std::size_t n = tangent_dimension_of<System>;
  LyapunovResult result;
  TangentVectorOf<n> v;
  v.fill(std::sqrt(1.0 / n));
  double log_growth = 0.0;
  for (int k = 0; k < alignment_periods + periods; ++k) {
    const double ta = t0 + k * period;
    const auto step =
        flow_with_jacobian(tangent, stepper, setup, x, mode, ta, t0 + (k + 1) * period);
    if (step.termination != Termination::completed || step.one_sided) {
      result.termination = step.one_sided ? Termination::no_tangent_map : step.termination;
      return result;
    }
    x = step.state;
    mode = step.mode;
    TangentVectorOf<n> w{};
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) w[i] += step.jacobian[i][j] * v[j];
    const double norm = tangent_norm<n>(w);
    if (k >= alignment_periods) log_growth += std::log(norm);
    if (!(norm > 0.0) || !std::isfinite(norm)) {
      result.exponent = norm > 0.0 ? std::numeric_limits<double>::quiet_NaN()
                                   : -std::numeric_limits<double>::infinity();
      result.periods = k + 1 - alignment_periods;
      return result;
    }
    for (std::size_t i = 0; i < n; ++i) v[i] = w[i] / norm;
  }
  result.periods = periods;
  result.exponent = log_growth / (periods * period);
  return result;
}

// With one stepper for all the periods: a stepper per period would cost the
// Taylor stepper's construction (its coefficient rows, about 42 KB) every
// period.
template <HasJacobian System>
LyapunovResult largest_lyapunov_exponent(const System& system, const FlowSetup& setup,
                                         typename System::State x, typename System::Mode mode,
                                         double t0, double period, int periods,
                                         int alignment_periods) {
  using Tangent = TangentOf<System>;
  const Tangent tangent{DecoratedSystem<System>(system)};
  return with_flow<Tangent>(setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
    return largest_lyapunov_exponent(tangent, stepper, setup, x, mode, t0, period, periods,
                                     alignment_periods);
  });
}

}  // namespace impactlab
