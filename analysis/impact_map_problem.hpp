// The impact map of one wall of a concrete system with Jacobians as a
// ContinuationProblem (continuation_problem.hpp): the state is (φ, q̇⁻, x₂⁻,
// …), the forcing phase of an impact with the wall and the system's
// tangent-space state just before it with q (on the wall) left out: (φ, q̇⁻)
// for one degree of freedom, (φ, θ̇⁻, φ̇_ball⁻) for the rigid pendulum with
// its spin free; and what a continuation on it needs to start: the first
// impact with the wall, the wall's witness, the impacts with it per orbit.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include <impactlab/analysis/chatter_onset.hpp>
#include <impactlab/analysis/contact_landing.hpp>
#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/map_evaluation.hpp>
#include <impactlab/analysis/saltation.hpp>
#include <impactlab/analysis/stroboscopic_map_problem.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>

namespace impactlab {

// The system that stops the run just before the reset of its `target`-th
// impact with wall `wall` (counted from 0), noting the times of those
// impacts; no contact suppressed.
template <HasJacobian System>
DecoratedSystem<System> stopping_at_wall_impact(const System& system,
                                                typename System::Mode flight_mode, int wall,
                                                int target, WallImpactTrace& trace,
                                                const ContactWindow& window = {},
                                                CrossingTrace* crossings = nullptr) {
  DecoratedSystem<System> decorated = suppressing_contacts(system, flight_mode, window, crossings);
  decorated.with_stop_at_wall_impact(wall, target, trace);
  return decorated;
}

// The state on witness k's zero at time t with the section point's
// components after the phase (q̇, x₂, …; bookkeeping components zero): q by
// Newton on the gap from q_guess; none where it does not converge.
template <HasJacobian System>
std::optional<typename System::State> state_on_wall(const System& system,
                                                    typename System::Mode flight_mode,
                                                    std::size_t witness, double t,
                                                    const OrbitPoint& section, double q_guess) {
  typename System::State x{};
  x[0] = q_guess;
  for (std::size_t i = 1; i < tangent_dimension_of<System>; ++i) x[i] = section[i];
  for (int iteration = 0; iteration < 30; ++iteration) {
    const double gap = system.witness(flight_mode, witness, x, t).value;
    const double slope = system.witness_gradient(flight_mode, witness, x, t)[0];
    if (!(std::fabs(slope) > 0.0) || !std::isfinite(gap)) return std::nullopt;
    const double dq = -gap / slope;
    x[0] += dq;
    if (std::fabs(dq) <= 4.0 * std::numeric_limits<double>::epsilon() * (1.0 + std::fabs(x[0])))
      break;
  }
  const double gap = system.witness(flight_mode, witness, x, t).value;
  if (!(std::fabs(gap) <= 1e-13 * (1.0 + std::fabs(x[0])))) return std::nullopt;
  return x;
}

// the first n components of a state: its part on the tangent space
template <std::size_t n, class State>
OrbitPoint tangent_orbit_point(const State& x) {
  return OrbitPoint(x.begin(), x.begin() + n);
}

// Where the run from state x (in mode) at t0 first hits wall `wall` before
// t_end: (time, the state just before, the witness); none if it does not.
struct WallImpact {
  double t = 0.0;
  OrbitPoint state{};  // (q, q̇, …) just before the impact, on the tangent space
  std::size_t witness = 0;
};
template <HasJacobian System>
std::optional<WallImpact> first_wall_impact(const System& system,
                                            const typename System::State& x,
                                            typename System::Mode mode, double t0, double t_end,
                                            int wall, const FlowSetup& setup) {
  WallImpactTrace impacts;
  const DecoratedSystem<System> stopping = stopping_at_wall_impact(system, mode, wall, 0, impacts);
  EventLog log(true);
  const auto run = with_flow<DecoratedSystem<System>>(
      setup.method, stepper_settings(stopping, setup), [&](auto& stepper) {
        return simulate(stopping, stepper, x, mode, t0, t_end, loop_options(setup), log);
      });
  if (!impacts.stopped) return std::nullopt;
  return WallImpact{impacts.stop_time, tangent_orbit_point<tangent_dimension_of<System>>(run.state),
                    impacts.stop_witness};
}

// The impact map of wall `wall` as a ContinuationProblem: the state is
// (φ, z⁻), φ = ω tᵢ the forcing phase of an impact with the wall and
// z⁻ = (q̇, x₂, …) the tangent-space state just before it without q; the map
// runs from that impact (applied at the start) to the `wall_impacts`-th next
// impact with the wall, the orbit's return after `period` forcing periods,
// and its image is
//     (φ + ω (tⱼ − tᵢ) − 2π·period, z⁻ at tⱼ),
// so that a fixed point is a period-n orbit. Its Jacobian is
//     M = L Φ S B:
// B takes (δφ, δz⁻) to the perturbation at the fixed time tᵢ before the
// impact (the impact point slides along the wall, q = q_w(t, z) from the
// wall's gap h(q, z, t) = 0, and the perturbed orbit reaches it δt = δφ/ω
// later: δx = (∂q_w/∂t δt + ∂q_w/∂z · δz, δz) − f⁻ δt); S is the saltation
// matrix of the start impact and Φ the saltation-corrected flow to tⱼ (both
// from the variational run, which applies the start impact as its first
// event); L projects onto the section: the perturbed orbit reaches the wall
// δtⱼ = −∇h·δx / ḣ later, so δφ' = ω δtⱼ and δzₖ' = δzₖ + fₖ δtⱼ.
template <HasJacobian System>
ContinuationProblem impact_map_problem(SystemOfParameter<System> make_system,
                                       typename System::Mode flight_mode, const FlowSetup& setup,
                                       int wall, std::size_t witness, double q_guess, int period,
                                       int wall_impacts, double forcing_omega_at_start) {
  using Mode = typename System::Mode;
  using Decorated = DecoratedSystem<System>;
  using Tangent = Variational<Decorated>;
  constexpr std::size_t n = tangent_dimension_of<System>;
  constexpr int samples_per_period = 96;
  struct Shared {
    SystemOfParameter<System> make_system;
    Mode flight_mode;
    FlowSetup setup;
    int wall;
    std::size_t witness;
    double q_guess;
    int period, wall_impacts;
  };
  auto shared = std::make_shared<Shared>(
      Shared{make_system, flight_mode, setup, wall, witness, q_guess, period, wall_impacts});

  ContinuationProblem problem;
  problem.dimension = n;
  problem.forcing_period_at_p = period * 2.0 * std::numbers::pi / forcing_omega_at_start;
  problem.phase = 0.0;
  problem.section_moves = false;
  problem.evaluate = [shared](const OrbitPoint& x, double p, double, bool detailed,
                              const ContactWindow& suppressed) {
    OrbitEvaluation result;
    const System system = shared->make_system(p);
    const double omega = forcing_omega_of(system);
    const double forcing_period = 2.0 * std::numbers::pi / omega;
    const double t0 = x[0] / omega;
    const double span = shared->period * forcing_period;
    const auto start =
        state_on_wall(system, shared->flight_mode, shared->witness, t0, x, shared->q_guess);
    if (!start) return result;
    CrossingTrace trace;
    WallImpactTrace impacts;
    ContactWindow window = suppressed;
    window.from += t0;
    window.to += t0;
    const Decorated stopping =
        stopping_at_wall_impact(system, shared->flight_mode, shared->wall, shared->wall_impacts,
                                impacts, window, &trace);
    const Tangent tangent(stopping);
    EventLog log(true);
    const int sample_count = detailed ? samples_per_period * shared->period - 1 : 0;
    GapSampler<System> sampler(system, shared->flight_mode, t0, span / (sample_count + 1),
                               sample_count);
    const auto run = with_flow<Tangent>(
        shared->setup.method, stepper_settings(tangent, shared->setup), [&](auto& stepper) {
          return simulate(tangent, stepper, tangent.start(*start, shared->flight_mode),
                          shared->flight_mode, t0, t0 + span + 0.5 * forcing_period,
                          loop_options(shared->setup), log, sampler);
        });
    // the run began with the impact at t0 and stopped at the target impact
    if (!impacts.stopped || impacts.times.empty() || impacts.times.front() != t0 ||
        run.mode != shared->flight_mode)
      return result;
    const auto end = Tangent::base_state(run.state);
    const double t1 = impacts.stop_time;
    // B: (δφ, δz⁻) to the perturbation before the impact at the fixed time t0
    typename System::State f{};
    system.rhs(shared->flight_mode, *start, f, t0);
    const TangentVectorOf<n> gradient =
        system.witness_gradient(shared->flight_mode, shared->witness, *start, t0);
    double gap_time_rate = system.witness(shared->flight_mode, shared->witness, *start, t0).rate;
    for (std::size_t i = 0; i < n; ++i) gap_time_rate -= gradient[i] * f[i];
    const double dq_dt = -gap_time_rate / gradient[0];
    TangentMatrixOf<n> to_start{};
    to_start[0][0] = (dq_dt - f[0]) / omega;
    for (std::size_t i = 1; i < n; ++i) {
      to_start[0][i] = -gradient[i] / gradient[0];  // ∂q_w/∂zᵢ
      to_start[i][0] = -f[i] / omega;
      to_start[i][i] = 1.0;
    }
    // L: the perturbation at t1 onto the section
    typename System::State f1{};
    system.rhs(shared->flight_mode, end, f1, t1);
    const TangentVectorOf<n> normal =
        system.witness_gradient(shared->flight_mode, impacts.stop_witness, end, t1);
    const double approach = system.witness(shared->flight_mode, impacts.stop_witness, end, t1).rate;
    if (!(std::fabs(approach) > 0.0)) return result;  // a graze: the section is tangent
    TangentMatrixOf<n> onto_section{};
    for (std::size_t j = 0; j < n; ++j) {
      onto_section[0][j] = -omega * normal[j] / approach;
      for (std::size_t i = 1; i < n; ++i)
        onto_section[i][j] = (i == j ? 1.0 : 0.0) - f1[i] * normal[j] / approach;
    }
    for (const auto& row :
         multiply(onto_section, multiply(Tangent::fundamental_matrix(run.state), to_start)))
      result.monodromy.emplace_back(row.begin(), row.end());
    result.image = tangent_orbit_point<n>(end);
    result.image[0] = x[0] + omega * (t1 - t0) - 2.0 * std::numbers::pi * shared->period;
    result.completed = std::all_of(result.image.begin(), result.image.end(),
                                   [](double v) { return std::isfinite(v); });
    result.span = span;
    result.omega = omega;
    // the orbit's events: after the start impact, up to the target impact
    const auto& records = log.records();
    note_events(records.begin() + static_cast<std::ptrdiff_t>(impacts.first_record) + 1,
                records.begin() + static_cast<std::ptrdiff_t>(impacts.stop_record) + 1, t0,
                result);
    // the landings from the start impact on, the target impact left out: at
    // the fixed point it is the start impact one orbit on, with the same
    // push, and the two would tie
    note_landing_push(system, records.begin() + static_cast<std::ptrdiff_t>(impacts.first_record),
                      records.begin() + static_cast<std::ptrdiff_t>(impacts.stop_record), t0,
                      result);
    note_chatter_margin(system,
                        records.begin() + static_cast<std::ptrdiff_t>(impacts.first_record) + 1,
                        records.begin() + static_cast<std::ptrdiff_t>(impacts.stop_record) + 1,
                        t0 + 2.0 * span, result);
    // the slowest impact. With the section's own wall, only the target
    // impact (the section's own, one orbit on) is a grazing candidate: the
    // driver solves it on the stroboscopic map (problem.strobe); another
    // impact with that wall is none (the count of the map would change)
    for (const auto& crossing : trace.crossings) {
      if (!(crossing.t > t0) || !(crossing.speed < result.min_impact_speed)) continue;
      result.min_impact_speed = crossing.speed;
      result.slowest_impact_time = crossing.t - t0;
      const bool own_wall = crossing.witness == static_cast<int>(shared->witness);
      result.slowest_impact_witness =
          !own_wall || crossing.t == impacts.stop_time ? crossing.witness : -1;
    }
    note_lowest_flight_gap<System>(sampler.samples, trace, t0, result);
    return result;
  };
  problem.gap_at = [shared](const OrbitPoint& x, double p, double, const ContactWindow& suppressed,
                            double t) {
    GapSample sample;
    const System system = shared->make_system(p);
    const double t0 = x[0] / forcing_omega_of(system);
    const auto start =
        state_on_wall(system, shared->flight_mode, shared->witness, t0, x, shared->q_guess);
    if (!start || suppressed.witness < 0) return sample;
    ContactWindow window = suppressed;
    window.from += t0;
    window.to += t0;
    const Decorated wrapped = suppressing_contacts(system, shared->flight_mode, window, nullptr);
    EventLog log(false);
    const auto run = with_flow<Decorated>(
        shared->setup.method, stepper_settings(wrapped, shared->setup), [&](auto& stepper) {
          return simulate(wrapped, stepper, *start, shared->flight_mode, t0, t0 + t,
                          loop_options(shared->setup), log);
        });
    if (run.termination != Termination::completed || run.mode != shared->flight_mode)
      return sample;
    const WitnessSample h =
        system.witness(run.mode, static_cast<std::size_t>(suppressed.witness), run.state, t0 + t);
    sample.completed = true;
    sample.value = h.value;
    sample.rate = h.rate;
    sample.state = tangent_orbit_point<tangent_dimension_of<System>>(run.state);
    return sample;
  };
  problem.transport = [](const OrbitPoint&, double, double, double) -> std::optional<OrbitPoint> {
    return std::nullopt;  // the impact section does not move
  };
  // the grazing of the section's own impact: on the stroboscopic map
  problem.section_witness = static_cast<int>(witness);
  problem.strobe = std::make_shared<const ContinuationProblem>(stroboscopic_map_problem<System>(
      make_system, flight_mode, setup, 0.0, period, forcing_omega_at_start));
  problem.to_strobe = [shared](const OrbitPoint& x, double p,
                               double phase) -> std::optional<OrbitPoint> {
    const System system = shared->make_system(p);
    const double omega = forcing_omega_of(system);
    const double t0 = x[0] / omega;
    const auto start =
        state_on_wall(system, shared->flight_mode, shared->witness, t0, x, shared->q_guess);
    if (!start) return std::nullopt;
    // the next ωt ≡ phase after the impact
    double shift = std::fmod(phase - x[0], 2.0 * std::numbers::pi);
    if (shift <= 0.0) shift += 2.0 * std::numbers::pi;
    const double reach = 0.1 * shared->period * 2.0 * std::numbers::pi / omega;
    const Decorated virtual_orbit = suppressing_contacts(
        system, shared->flight_mode,
        ContactWindow{static_cast<int>(shared->witness), t0 - reach, t0 + reach}, nullptr);
    EventLog log(false);
    const auto run = with_flow<Decorated>(
        shared->setup.method, stepper_settings(virtual_orbit, shared->setup), [&](auto& stepper) {
          return simulate(virtual_orbit, stepper, *start, shared->flight_mode, t0,
                          t0 + shift / omega, loop_options(shared->setup), log);
        });
    if (run.termination != Termination::completed || run.mode != shared->flight_mode)
      return std::nullopt;
    return tangent_orbit_point<tangent_dimension_of<System>>(run.state);
  };
  return problem;
}

// The impacts with wall `wall` from one at (φ, z⁻) until (period + ½)
// forcing periods later: the count whose last lands nearest `period`
// periods on (the orbit's impacts with the wall per period), or 0.
template <HasJacobian System>
int wall_impacts_per_orbit(const System& system, typename System::Mode flight_mode,
                           const FlowSetup& setup, int wall, std::size_t witness, double q_guess,
                           const OrbitPoint& x, int period) {
  const double omega = forcing_omega_of(system);
  const double t0 = x[0] / omega, span = period * 2.0 * std::numbers::pi / omega;
  const auto start = state_on_wall(system, flight_mode, witness, t0, x, q_guess);
  if (!start) return 0;
  WallImpactTrace impacts;
  const DecoratedSystem<System> counting = stopping_at_wall_impact(
      system, flight_mode, wall, std::numeric_limits<int>::max(), impacts);
  EventLog log(true);
  with_flow<DecoratedSystem<System>>(
      setup.method, stepper_settings(counting, setup), [&](auto& stepper) {
        return simulate(counting, stepper, *start, flight_mode, t0,
                        t0 + span + 0.5 * span / period, loop_options(setup), log);
      });
  if (impacts.times.size() < 2 || impacts.times.front() != t0) return 0;
  int best = 0;
  for (std::size_t j = 1; j < impacts.times.size(); ++j)
    if (best == 0 || std::fabs(impacts.times[j] - t0 - span) <
                         std::fabs(impacts.times[static_cast<std::size_t>(best)] - t0 - span))
      best = static_cast<int>(j);
  return best;
}

// The witness whose zero at (φ, z⁻) is an impact with wall `wall` (the run
// from there begins with that impact), and q there; none if no witness is.
template <HasJacobian System>
std::optional<std::pair<std::size_t, double>> wall_witness(const System& system,
                                                           typename System::Mode flight_mode,
                                                           const FlowSetup& setup, int wall,
                                                           const OrbitPoint& x, double q_guess) {
  const double omega = forcing_omega_of(system);
  const double t0 = x[0] / omega;
  for (std::size_t k = 0; k < system.witness_count(flight_mode); ++k) {
    const auto start = state_on_wall(system, flight_mode, k, t0, x, q_guess);
    if (!start) continue;
    WallImpactTrace impacts;
    const DecoratedSystem<System> stopping =
        stopping_at_wall_impact(system, flight_mode, wall, 0, impacts);
    EventLog log(true);
    with_flow<DecoratedSystem<System>>(
        setup.method, stepper_settings(stopping, setup), [&](auto& stepper) {
          return simulate(stopping, stepper, *start, flight_mode, t0, t0 + 1e-3 / omega,
                          loop_options(setup), log);
        });
    if (impacts.stopped && impacts.stop_time == t0 && impacts.stop_witness == k)
      return std::pair<std::size_t, double>{k, (*start)[0]};
  }
  return std::nullopt;
}

}  // namespace impactlab
