// The Lyapunov spectrum: all N exponents of a trajectory, by carrying N
// orthonormal tangent vectors through one forcing period at a time with the
// period's Jacobian (the variational equations through flights, saltation
// matrices at events: analysis/floquet.hpp's flow_with_jacobian) and
// re-orthonormalising them by a Householder QR decomposition,
//     J_k Q_{k−1} = Q_k R_k,   λ_i = Σ_k ln |(R_k)_ii| / (K T),
// averaged over K periods of length T after `alignment_periods` periods that
// let the vectors turn into the Oseledets directions (Benettin et al. 1980;
// Eckmann & Ruelle 1985, Rev. Mod. Phys. 57, 617).
//
// Through an accumulation of impacts ending at rest, or a sticking phase, the
// tangent map is that of the constrained motion: it merges nearby states, the
// Jacobian loses rank, and the directions it collapses have (R_k)_ii = 0
// (below the QR's round-off, `collapse_tolerance`): their exponents are −∞,
// for the rest of the run, never NaN.
//
// The first tangent vector starts along (1, …, 1)/√N, as the largest
// exponent's does (largest_lyapunov_exponent), and the QR carries it exactly
// as that method does (J q / |J q|): λ1 is the largest exponent, to round-off.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/section.hpp>

namespace impactlab {

// A direction whose stretch over one period, |(R_k)_ii|, is below this
// fraction of the period's largest column of J_k Q_{k−1} is collapsed. A
// Householder QR is backward stable, with an error of about N ε |J Q| in R
// (ε = 2.2e-16), and the tangent run that made J (each step linear in Φ)
// keeps the rank a contact removed only to round-off: a collapsed direction
// comes out at 1e-16 to 1e-13 of the largest, not at zero. A finite
// exponent more than ln(1e12)/T ≈ 27.6/T below the largest is beyond what
// one period's Jacobian resolves in double precision, and is reported as
// collapsed too.
inline constexpr double collapse_tolerance = 1e-12;

// The QR re-orthonormalisation and the running sums, for an N of run time
// (compiled once, lyapunov_spectrum.cpp, with Eigen's Householder QR).
class LyapunovSpectrumAccumulator {
 public:
  // N tangent vectors, the first along (1, …, 1)/√N; `period` (time units)
  // converts the sums of logarithms into exponents.
  LyapunovSpectrumAccumulator(std::size_t dimension, double period);

  // One period's Jacobian J (row-major N × N): Q ← the Q of J Q, and, when
  // `averaging`, each ln |R_ii| added to its sum (−∞ for a collapsed
  // direction). False where J is not finite.
  bool advance(const double* jacobian, bool averaging);

  [[nodiscard]] std::size_t dimension() const { return dimension_; }
  [[nodiscard]] int periods_averaged() const { return periods_averaged_; }
  // the running estimate λ_i = sum_i / (periods averaged × T), 1/time unit
  [[nodiscard]] std::vector<double> exponents() const;

 private:
  std::size_t dimension_;
  double period_;
  std::vector<double> basis_;  // Q, row-major N × N, orthonormal columns
  std::vector<double> log_sums_;  // Σ ln |R_ii| over the periods averaged
  int periods_averaged_ = 0;
};

// How far the running estimate still moves: for each exponent, half the range
// (max − min) of its running estimate over the last quarter of the averaging
// periods (at least the last two), in 1/time unit; 0 for an exponent at −∞.
class RunningSpread {
 public:
  RunningSpread(std::size_t dimension, int periods);
  // the running estimate after `period` (1-based) of `periods` averaged
  void add(int period, const std::vector<double>& running);
  [[nodiscard]] std::vector<double> half_ranges(const std::vector<double>& final) const;

 private:
  int first_counted_;  // the first period of the last quarter
  std::vector<double> lowest_, highest_;
};

struct LyapunovSpectrumResult {
  // λ1 … λN (1/time unit), in the order of the QR's columns (descending for
  // a trajectory whose Jacobians are generic); −∞ for a collapsed direction;
  // NaN where the run stopped (`termination` says why)
  std::vector<double> exponents;
  std::vector<double> errors;  // RunningSpread's half ranges (1/time unit)
  int periods = 0;             // forcing periods averaged over
  std::uint64_t impacts = 0;   // impacts in those periods
  Termination termination = Termination::completed;
};

// The spectrum along the trajectory from (t0, x): `alignment_periods`
// periods of length `period` turn the vectors, `periods` more are averaged;
// the running estimate after each averaged period goes to `sink` (may be
// null). A trajectory that crosses an event with a one-sided tangent map gives
// NaN and no_tangent_map, as the largest exponent does.
// All its periods with the caller's stepper (analysis/floquet.hpp).
template <HasJacobian System, class Stepper>
LyapunovSpectrumResult lyapunov_spectrum(const Variational<System>& tangent, Stepper& stepper,
                                         const FlowSetup& setup, typename System::State x,
                                         typename System::Mode mode, double t0, double period,
                                         int periods, int alignment_periods,
                                         LyapunovSpectrumSink* sink) {
  constexpr std::size_t n = tangent_dimension_of<System>;
  LyapunovSpectrumResult result;
  result.exponents.assign(n, std::numeric_limits<double>::quiet_NaN());
  result.errors = result.exponents;
  LyapunovSpectrumAccumulator accumulator(n, period);
  RunningSpread spread(n, periods);
  if (sink != nullptr) sink->begin(n);
  for (int k = 0; k < alignment_periods + periods; ++k) {
    const double t_end = t0 + (k + 1) * period;
    const auto step = flow_with_jacobian(tangent, stepper, setup, x, mode, t0 + k * period, t_end);
    if (step.termination != Termination::completed || step.one_sided) {
      result.termination = step.one_sided ? Termination::no_tangent_map : step.termination;
      result.periods = accumulator.periods_averaged();
      return result;
    }
    x = step.state;
    mode = step.mode;
    std::array<double, n * n> jacobian;
    for (std::size_t i = 0; i < n; ++i)
      std::copy_n(step.jacobian[i].begin(), n, jacobian.begin() + i * n);
    const bool averaging = k >= alignment_periods;
    if (!accumulator.advance(jacobian.data(), averaging)) {
      result.termination = Termination::non_finite_state;
      result.periods = accumulator.periods_averaged();
      return result;
    }
    if (!averaging) continue;
    result.impacts += step.impacts;
    const std::vector<double> running = accumulator.exponents();
    spread.add(accumulator.periods_averaged(), running);
    if (sink != nullptr) sink->write(t_end, running);
  }
  result.periods = accumulator.periods_averaged();
  result.exponents = accumulator.exponents();
  result.errors = spread.half_ranges(result.exponents);
  return result;
}

// With one stepper for all the periods (as largest_lyapunov_exponent).
template <HasJacobian System>
LyapunovSpectrumResult lyapunov_spectrum(const System& system, const FlowSetup& setup,
                                         typename System::State x, typename System::Mode mode,
                                         double t0, double period, int periods,
                                         int alignment_periods,
                                         LyapunovSpectrumSink* sink = nullptr) {
  using Tangent = TangentOf<System>;
  const Tangent tangent{DecoratedSystem<System>(system)};
  return with_flow<Tangent>(setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
    return lyapunov_spectrum(tangent, stepper, setup, x, mode, t0, period, periods,
                             alignment_periods, sink);
  });
}

}  // namespace impactlab
