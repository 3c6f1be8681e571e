// The section map of a concrete system with Jacobians as a ContinuationProblem
// (analysis/continuation.hpp): Pⁿ(x; p) from the section ωt ≡ phase, its
// saltation-corrected monodromy, the impact signature, the slowest impact and
// the lowest flight gap (sampled), and the gap along the orbit with one
// wall's contacts suppressed near a time (the virtual orbit of a grazing
// point's extended system).
#pragma once

#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/curve_continuation.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/saltation.hpp>
#include <impactlab/analysis/scene_boundary.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/integrate/taylor_series.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

// The forcing frequency of a system (rad/s): parameters().omega of the
// built-in oscillators, forcing_frequency() of a model file's.
template <class System>
double forcing_omega_of(const System& system) {
  if constexpr (requires { system.forcing_frequency(); })
    return system.forcing_frequency();
  else
    return system.parameters().omega;
}

// The system with witness `window.witness` suppressed in flight mode between
// the absolute times window.from and window.to, noting every crossing in
// flight mode into `trace` (where given): the grazing extended system.
template <HasJacobian System>
DecoratedSystem<System> suppressing_contacts(const System& system,
                                             typename System::Mode flight_mode,
                                             const ContactWindow& window, CrossingTrace* trace) {
  DecoratedSystem<System> decorated(system);
  decorated.with_suppressed_contacts(flight_mode, window, trace);
  return decorated;
}

// Samples of the wall gaps in flight, for the lowest flight gap.
template <class Base>
class GapSampler {
 public:
  using Mode = typename Base::Mode;
  GapSampler(const Base& base, Mode flight_mode, double t0, double spacing, int count)
      : base_(base), flight_mode_(flight_mode), t0_(t0), spacing_(spacing), count_(count) {}
  [[nodiscard]] double next_time() const {
    return next_ < count_ ? t0_ + (next_ + 1) * spacing_ : INFINITY;
  }
  template <class State>
  void observe(double t, const State& v, Mode mode) {
    ++next_;
    typename Base::State x;
    std::copy_n(v.begin(), x.size(), x.begin());
    Sample sample{t, mode == flight_mode_, {}};
    for (std::size_t k = 0; k < Base::max_witnesses; ++k)
      sample.gap[k] = k < base_.witness_count(mode) ? base_.witness(mode, k, x, t).value : INFINITY;
    samples.push_back(sample);
  }
  struct Sample {
    double t;
    bool flight;
    std::array<double, Base::max_witnesses> gap;
  };
  std::vector<Sample> samples;

 private:
  const Base& base_;
  Mode flight_mode_;
  double t0_, spacing_;
  int count_, next_ = 0;
};

// The impacts, contact phases, signature and event times (since t0) of the
// event records [begin, end) into `result`.
template <class Records>
void note_events(Records begin, Records end, double t0, OrbitEvaluation& result) {
  for (auto event = begin; event != end; ++event) {
    result.event_times.push_back(event->t - t0);
    const std::string wall = event->wall > 0 ? "+" + std::to_string(event->wall)
                                             : std::to_string(event->wall);
    if (event->kind == EventKind::impact) {
      ++result.impacts;
      result.signature += (result.signature.empty() ? "" : " ") + wall;
    } else if (event->kind == EventKind::contact_start) {
      ++result.contact_phases;
      result.signature += (result.signature.empty() ? "c" : " c") + wall;
    }
  }
}

// The lowest interior local minimum of each gap between samples in flight,
// away from crossings, refined by the parabola through three samples.
template <class System, class Samples>
void note_lowest_flight_gap(const Samples& samples, const CrossingTrace& trace, double t0,
                            OrbitEvaluation& result) {
  for (std::size_t j = 1; j + 1 < samples.size(); ++j) {
    if (!samples[j - 1].flight || !samples[j].flight || !samples[j + 1].flight) continue;
    for (std::size_t k = 0; k < System::max_witnesses; ++k) {
      const double a = samples[j - 1].gap[k], b = samples[j].gap[k], c = samples[j + 1].gap[k];
      if (!(b <= a && b <= c) || !std::isfinite(a + b + c)) continue;
      const bool crossed = std::any_of(
          trace.crossings.begin(), trace.crossings.end(), [&](const auto& crossing) {
            return crossing.witness == static_cast<int>(k) && crossing.t >= samples[j - 1].t &&
                   crossing.t <= samples[j + 1].t;
          });
      if (crossed) continue;
      // the parabola through the three samples
      const double curvature = a - 2.0 * b + c;
      const double offset = curvature > 0.0 ? 0.5 * (a - c) / curvature : 0.0;
      const double lowest = b - 0.125 * (a - c) * offset;
      if (lowest < result.min_flight_gap) {
        result.min_flight_gap = lowest;
        result.min_flight_gap_time = samples[j].t + offset * (samples[j + 1].t - samples[j].t) - t0;
        result.min_flight_gap_witness = static_cast<int>(k);
      }
    }
  }
}

// The problem for p ↦ make_system(p) (forcing_omega_of gives its forcing
// frequency), section ωt ≡ phase, period n, from flight mode.
template <HasJacobian System, class MakeSystem>
ContinuationProblem section_map_problem(MakeSystem make_system, typename System::Mode flight_mode,
                                        const FlowSetup& setup, double phase, int period,
                                        double forcing_omega_at_start) {
  using Mode = typename System::Mode;
  using Wrapped = DecoratedSystem<System>;
  using Tangent = Variational<Wrapped>;
  constexpr std::size_t n = tangent_dimension_of<System>;  // the OrbitPoint's components
  constexpr int samples_per_period = 96;
  struct Shared {
    MakeSystem make_system;
    Mode flight_mode;
    FlowSetup setup;
    double phase;
    int period;
  };
  auto shared = std::make_shared<Shared>(Shared{make_system, flight_mode, setup, phase, period});

  ContinuationProblem problem;
  problem.forcing_period_at_p = period * 2.0 * std::numbers::pi / forcing_omega_at_start;
  problem.phase = phase;
  problem.dimension = n;
  problem.evaluate = [shared](const OrbitPoint& x, double p, double section_phase, bool detailed,
                              const ContactWindow& suppressed) {
    OrbitEvaluation result;
    const System system = shared->make_system(p);
    const double omega = forcing_omega_of(system);
    const double t0 = section_phase / omega;
    const double span = shared->period * 2.0 * std::numbers::pi / omega;
    CrossingTrace trace;
    ContactWindow window = suppressed;
    window.from += t0;
    window.to += t0;
    const Wrapped wrapped = suppressing_contacts(system, shared->flight_mode, window, &trace);
    const Tangent tangent(wrapped);
    typename System::State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    EventLog log(true);
    const int sample_count = detailed ? samples_per_period * shared->period - 1 : 0;
    GapSampler<System> sampler(system, shared->flight_mode, t0, span / (sample_count + 1),
                               sample_count);
    const auto run = with_flow<Tangent>(
        shared->setup.method, stepper_settings(tangent, shared->setup), [&](auto& stepper) {
          return simulate(tangent, stepper, tangent.start(x0, shared->flight_mode),
                          shared->flight_mode, t0, t0 + span, loop_options(shared->setup), log,
                          sampler);
        });
    if (run.termination != Termination::completed || run.mode != shared->flight_mode) return result;
    const auto state = Tangent::base_state(run.state);
    result.completed = std::all_of(state.begin(), state.begin() + n,
                                   [](double component) { return std::isfinite(component); });
    result.image.assign(state.begin(), state.begin() + n);
    for (const auto& row : Tangent::fundamental_matrix(run.state))
      result.monodromy.emplace_back(row.begin(), row.end());
    result.span = span;
    result.omega = omega;
    note_events(log.records().begin(), log.records().end(), t0, result);
    for (const auto& crossing : trace.crossings) {
      if (crossing.speed < result.min_impact_speed) {
        result.min_impact_speed = crossing.speed;
        result.slowest_impact_time = crossing.t - t0;
        result.slowest_impact_witness = crossing.witness;
      }
    }
    note_lowest_flight_gap<System>(sampler.samples, trace, t0, result);
    return result;
  };
  problem.gap_at = [shared](const OrbitPoint& x, double p, double section_phase,
                            const ContactWindow& suppressed, double t) {
    GapSample sample;
    const System system = shared->make_system(p);
    const double t0 = section_phase / forcing_omega_of(system);
    ContactWindow window = suppressed;
    window.from += t0;
    window.to += t0;
    const Wrapped wrapped = suppressing_contacts(system, shared->flight_mode, window, nullptr);
    typename System::State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    EventLog log(false);
    const auto run = with_flow<Wrapped>(
        shared->setup.method, stepper_settings(wrapped, shared->setup), [&](auto& stepper) {
          return simulate(wrapped, stepper, x0, shared->flight_mode, t0, t0 + t,
                          loop_options(shared->setup), log);
        });
    if (run.termination != Termination::completed || run.mode != shared->flight_mode ||
        suppressed.witness < 0)
      return sample;
    const WitnessSample h =
        system.witness(run.mode, static_cast<std::size_t>(suppressed.witness), run.state, t0 + t);
    sample.completed = true;
    sample.value = h.value;
    sample.rate = h.rate;
    sample.state.assign(run.state.begin(), run.state.begin() + n);
    return sample;
  };
  problem.transport = [shared](const OrbitPoint& x, double p, double from,
                               double to) -> std::optional<OrbitPoint> {
    const System system = shared->make_system(p);
    const double omega = forcing_omega_of(system);
    const double shift = std::remainder(to - from, 2.0 * std::numbers::pi);
    const double t0 = from / omega;
    const double t1 = t0 + (shift < 0.0 ? shift + 2.0 * std::numbers::pi : shift) / omega;
    typename System::State x0{};
    std::copy_n(x.begin(), n, x0.begin());
    EventLog log(false);
    const auto run = with_flow<System>(
        shared->setup.method, stepper_settings(system, shared->setup), [&](auto& stepper) {
          return simulate(system, stepper, x0, shared->flight_mode, t0, t1,
                          loop_options(shared->setup), log);
        });
    if (run.termination != Termination::completed) return std::nullopt;
    return OrbitPoint(run.state.begin(), run.state.begin() + n);
  };
  return problem;
}

// --- the impact section: the map from one impact with a wall to a later one ---

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

// The state on witness k's zero at time t with rate qdot: q by Newton on the
// gap from q_guess; none where it does not converge.
template <HasJacobian System>
std::optional<typename System::State> state_on_wall(const System& system,
                                                    typename System::Mode flight_mode,
                                                    std::size_t witness, double t, double qdot,
                                                    double q_guess) {
  typename System::State x{};
  x[0] = q_guess;
  x[1] = qdot;
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

// Where the run from state x (in mode) at t0 first hits wall `wall` before
// t_end: (time, the state just before, the witness); none if it does not.
struct WallImpact {
  double t = 0.0;
  OrbitPoint state{};  // (q, q̇) just before the impact
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
  return WallImpact{impacts.stop_time, {run.state[0], run.state[1]}, impacts.stop_witness};
}

// The impact map of wall `wall` as a ContinuationProblem: the state is
// (φ, q̇⁻), φ = ω tᵢ the forcing phase of an impact with the wall and q̇⁻ the
// rate just before it; the map runs from that impact (applied at the start)
// to the `wall_impacts`-th next impact with the wall, the orbit's return
// after `period` forcing periods, and its image is
//     (φ + ω (tⱼ − tᵢ) − 2π·period, q̇⁻ at tⱼ),
// so that a fixed point is a period-n orbit. Its Jacobian is
//     M = L Φ S B:
// B takes (δφ, δq̇⁻) to the perturbation at the fixed time tᵢ before the
// impact (the impact point slides along the wall, q = q_w(t, q̇), and the
// perturbed orbit reaches it δt = δφ/ω later: δx = (∂q_w/∂t δt + ∂q_w/∂q̇ δq̇,
// δq̇) − f⁻ δt); S is the saltation matrix of the start impact and Φ the
// saltation-corrected flow to tⱼ (both from the variational run, which
// applies the start impact as its first event); L projects onto the section:
// the perturbed orbit reaches the wall δtⱼ = −∇h·δx / ḣ later, so
// δφ' = ω δtⱼ and δq̇' = δq̇ + f₂ δtⱼ.
template <HasJacobian System, class MakeSystem>
ContinuationProblem impact_map_problem(MakeSystem make_system, typename System::Mode flight_mode,
                                       const FlowSetup& setup, int wall, std::size_t witness,
                                       double q_guess, int period, int wall_impacts,
                                       double forcing_omega_at_start) {
  using Mode = typename System::Mode;
  using Decorated = DecoratedSystem<System>;
  using Tangent = Variational<Decorated>;
  constexpr int samples_per_period = 96;
  struct Shared {
    MakeSystem make_system;
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
  problem.forcing_period_at_p = period * 2.0 * std::numbers::pi / forcing_omega_at_start;
  problem.phase = 0.0;
  problem.section_moves = false;
  problem.evaluate = [shared](const OrbitPoint& x, double p, double, bool detailed,
                              const ContactWindow& suppressed) {
    OrbitEvaluation result;
    const System system = shared->make_system(p);
    const double omega = system.parameters().omega;
    const double forcing_period = 2.0 * std::numbers::pi / omega;
    const double t0 = x[0] / omega;
    const double span = shared->period * forcing_period;
    const auto start = state_on_wall(system, shared->flight_mode, shared->witness, t0, x[1],
                                     shared->q_guess);
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
    // B: (δφ, δq̇⁻) to the perturbation before the impact at the fixed time t0
    typename System::State f{};
    system.rhs(shared->flight_mode, *start, f, t0);
    const TangentVector gradient =
        system.witness_gradient(shared->flight_mode, shared->witness, *start, t0);
    const double gap_time_rate =
        system.witness(shared->flight_mode, shared->witness, *start, t0).rate -
        (gradient[0] * f[0] + gradient[1] * f[1]);
    const double dq_dt = -gap_time_rate / gradient[0], dq_dqdot = -gradient[1] / gradient[0];
    const TangentMatrix to_start{{{(dq_dt - f[0]) / omega, dq_dqdot}, {-f[1] / omega, 1.0}}};
    // L: the perturbation at t1 onto the section
    typename System::State f1{};
    system.rhs(shared->flight_mode, end, f1, t1);
    const TangentVector normal =
        system.witness_gradient(shared->flight_mode, impacts.stop_witness, end, t1);
    const double approach = system.witness(shared->flight_mode, impacts.stop_witness, end, t1).rate;
    if (!(std::fabs(approach) > 0.0)) return result;  // a graze: the section is tangent
    const TangentMatrix onto_section{
        {{-omega * normal[0] / approach, -omega * normal[1] / approach},
         {-f1[1] * normal[0] / approach, 1.0 - f1[1] * normal[1] / approach}}};
    for (const auto& row :
         multiply(onto_section, multiply(Tangent::fundamental_matrix(run.state), to_start)))
      result.monodromy.emplace_back(row.begin(), row.end());
    result.image = {x[0] + omega * (t1 - t0) - 2.0 * std::numbers::pi * shared->period, end[1]};
    result.completed = std::isfinite(result.image[0]) && std::isfinite(result.image[1]);
    result.span = span;
    result.omega = omega;
    // the orbit's events: after the start impact, up to the target impact
    const auto& records = log.records();
    note_events(records.begin() + static_cast<std::ptrdiff_t>(impacts.first_record) + 1,
                records.begin() + static_cast<std::ptrdiff_t>(impacts.stop_record) + 1, t0,
                result);
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
    const double t0 = x[0] / system.parameters().omega;
    const auto start = state_on_wall(system, shared->flight_mode, shared->witness, t0, x[1],
                                     shared->q_guess);
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
    sample.state = {run.state[0], run.state[1]};
    return sample;
  };
  problem.transport = [](const OrbitPoint&, double, double, double) -> std::optional<OrbitPoint> {
    return std::nullopt;  // the impact section does not move
  };
  // the grazing of the section's own impact: on the stroboscopic map
  problem.section_witness = static_cast<int>(witness);
  problem.strobe = std::make_shared<const ContinuationProblem>(section_map_problem<System>(
      make_system, flight_mode, setup, 0.0, period, forcing_omega_at_start));
  problem.to_strobe = [shared](const OrbitPoint& x, double p,
                               double phase) -> std::optional<OrbitPoint> {
    const System system = shared->make_system(p);
    const double omega = system.parameters().omega;
    const double t0 = x[0] / omega;
    const auto start = state_on_wall(system, shared->flight_mode, shared->witness, t0, x[1],
                                     shared->q_guess);
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
    return OrbitPoint{run.state[0], run.state[1]};
  };
  return problem;
}

// The impacts with wall `wall` from one at (φ, q̇⁻) until (period + ½)
// forcing periods later: the count whose last lands nearest `period`
// periods on (the orbit's impacts with the wall per period), or 0.
template <HasJacobian System>
int wall_impacts_per_orbit(const System& system, typename System::Mode flight_mode,
                           const FlowSetup& setup, int wall, std::size_t witness, double q_guess,
                           const OrbitPoint& x, int period) {
  const double omega = system.parameters().omega;
  const double t0 = x[0] / omega, span = period * 2.0 * std::numbers::pi / omega;
  const auto start = state_on_wall(system, flight_mode, witness, t0, x[1], q_guess);
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

// The witness whose zero at (φ, q̇⁻) is an impact with wall `wall` (the run
// from there begins with that impact), and q there; none if no witness is.
template <HasJacobian System>
std::optional<std::pair<std::size_t, double>> wall_witness(const System& system,
                                                           typename System::Mode flight_mode,
                                                           const FlowSetup& setup, int wall,
                                                           const OrbitPoint& x, double q_guess) {
  const double omega = system.parameters().omega;
  const double t0 = x[0] / omega;
  for (std::size_t k = 0; k < system.witness_count(flight_mode); ++k) {
    const auto start = state_on_wall(system, flight_mode, k, t0, x[1], q_guess);
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

// The curve of the first located fold, period doubling or grazing point (of
// job.curve_type where given) of branch `index`, in (job.parameter,
// job.second_parameter), into `curve`; false, with why in `note`, where the
// branch has none. map_at(scene, period) is the branch's section map of the
// system `scene` describes, continued in job.parameter (stroboscopic or
// impact section). On the impact section, a grazing of the section's own
// impact is followed on the stroboscopic map half a forcing period after the
// impact (as the branch located it: that section is tangent to the flow
// there), and each point is carried back onto the impact section:
// (φ, q̇⁻) = (phase + ω (t_g − nT), q̇(t_g)), graze time 0.
template <HasJacobian System, class SystemAt, class MapAt>
bool continue_curve_of(const ContinuationJobResult& result, std::size_t index, CurveResult& curve,
                       std::string& note, SystemAt system_at, MapAt map_at,
                       typename System::Mode flight_mode, const Scene& scene,
                       const ContinuationJob& job, const FlowSetup& setup, double omega) {
  const ContinuationResult& branch = result.branches.at(index).result;
  const int period = result.branches[index].period;
  const auto wanted = [&](const BifurcationPoint& p) {
    if (!p.located) return false;
    const std::string type = p.type == "branch_point" ? "fold" : p.type;
    if (!job.curve_type.empty()) return type == job.curve_type;
    return type == "fold" || type == "period_doubling" || type == "grazing";
  };
  const auto found = std::find_if(branch.points.begin(), branch.points.end(), wanted);
  if (found == branch.points.end()) {
    note = "no located " +
           (job.curve_type.empty() ? std::string("fold, period doubling or grazing")
                                   : job.curve_type) +
           " point on the branch to start the curve from";
    return false;
  }
  CurveRequest request;
  request.type = found->type == "branch_point" ? "fold" : found->type;
  request.from1 = job.from;
  request.to1 = job.to;
  request.from2 = job.second_from;
  request.to2 = job.second_to;
  request.p1 = found->parameter;
  request.state = found->state;
  request.graze_time = found->graze_time;
  request.graze_witness = found->graze_witness;
  request.max_points = job.numerics.max_points;
  request.tolerance = job.numerics.tolerance;
  // the branch's largest step, as a fraction of the first parameter's range
  if (job.numerics.max_step > 0.0) request.max_step = job.numerics.max_step / std::fabs(job.to - job.from);
  const auto scene_at = [scene, job](double p2) {
    Scene at = scene;
    at.values[job.second_parameter] = p2;
    return at;
  };
  const ContinuationProblem at_start = map_at(scene_at(job.second_from), period);
  const bool section_wall_graze = request.type == "grazing" && at_start.section_witness >= 0 &&
                                  found->graze_witness == at_start.section_witness;
  TwoParameterProblem problem;
  double strobe_phase = 0.0;  // rad: the stroboscopic section of a section-wall graze
  if (section_wall_graze) {
    strobe_phase = found->state[0] + std::numbers::pi;
    const auto carried = at_start.to_strobe(found->state, found->parameter, strobe_phase);
    if (!carried) {
      note = "the grazing point could not be carried to the stroboscopic section";
      return false;
    }
    Scene at = scene_at(job.second_from);
    at.values[job.parameter] = found->parameter;
    const double span = period * 2.0 * std::numbers::pi / forcing_omega_of(system_at(at));
    request.state = *carried;
    request.graze_time = span - 0.5 * span / period;
    problem.at = [scene_at, job, system_at, flight_mode, setup, omega, period,
                  strobe_phase](double p2) {
      auto make_system = [scene = scene_at(p2), job, system_at](double p1) {
        Scene at = scene;
        at.values[job.parameter] = p1;
        return system_at(at);
      };
      return section_map_problem<System>(make_system, flight_mode, setup, strobe_phase, period,
                                         omega);
    };
  } else {
    problem.at = [scene_at, map_at, period](double p2) { return map_at(scene_at(p2), period); };
  }
  curve = continue_curve(problem, request);
  if (section_wall_graze) {
    // back onto the impact section
    for (CurvePoint& point : curve.curve) {
      const ContinuationProblem strobe = problem.at(point.p2);
      Scene at = scene_at(point.p2);
      at.values[job.parameter] = point.p1;
      const double point_omega = forcing_omega_of(system_at(at));
      const double span = period * 2.0 * std::numbers::pi / point_omega;
      const double half_width = 0.1 * strobe.forcing_period_at_p;
      const GapSample touch = strobe.gap_at(
          point.state, point.p1, strobe_phase,
          ContactWindow{found->graze_witness, point.graze_time - half_width,
                        point.graze_time + half_width},
          point.graze_time);
      point.state = {strobe_phase + point_omega * (point.graze_time - span),
                     touch.completed ? touch.state[1] : std::numeric_limits<double>::quiet_NaN()};
      point.graze_time = 0.0;
    }
  }
  return true;
}

// A job whose start was not found: one branch stopped at its start, with why.
inline ContinuationJobResult no_start(ContinuationJobResult& result, const ContinuationJob& job,
                                      const std::string& why) {
  ContinuationResult stopped;
  stopped.stop_reason = "start_not_converged";
  stopped.stop_detail = why;
  result.branches.push_back({job.period, stopped});
  return result;
}

// A continuation from a scene: the start from a transient from the scene's
// initial state at p = from (or the job's start), the branch, then, for each
// period doubling asked for, the doubled orbit's branch from the first period
// doubling located on the previous one (along the −1 eigenvector).
// system_at(scene) builds the system a scene describes.
template <HybridSystem System, class SystemAt>
ContinuationJobResult run_continuation(SystemAt system_at, typename System::Mode flight_mode,
                                       const typename System::State& initial_state,
                                       const Scene& job_scene, const ContinuationJob& job,
                                       const std::vector<SceneBoundary>& boundaries = {}) {
  ContinuationJobResult result;
  // a two-parameter job runs its branch at second_parameter = second_from
  Scene scene = job_scene;
  if (!job.second_parameter.empty()) scene.values[job.second_parameter] = job.second_from;
  if constexpr (!HasJacobian<System>) {
    result.note = "this oscillator/model has no Jacobians";
    return result;
  } else {
    result.available = true;
    Scene start_scene = scene;
    start_scene.values[job.parameter] = job.from;
    const System start_system = system_at(start_scene);
    const double omega = forcing_omega_of(start_system);
    const FlowSetup setup = flow_setup(scene);
    [[maybe_unused]] double wall_q = 0.0;  // the impact section: q on the wall at the start (a guess)
    ContinuationRequest request = job.numerics;
    request.from = job.from;
    request.to = job.to;
    constexpr std::size_t n = tangent_dimension_of<System>;
    result.dimension = n;
    // the impact section's state is (phase, rate before the impact): one
    // degree of freedom
    if (job.impact_wall != 0 && n != 2)
      throw BadInput("--section", "impact:" + std::to_string(job.impact_wall),
                     "the impact section takes a one-degree-of-freedom orbit; use the strobe");
    if (job.has_start) {
      if (job.start.size() != n)
        throw BadInput("start", std::to_string(job.start.size()) + " numbers",
                       "expected " + std::to_string(n) + " (the orbit's state on the section)");
      request.start = job.start;
    } else {
      const double forcing_period = 2.0 * std::numbers::pi / omega;
      const double t0 = start_scene.number("t0");
      const double after = t0 + job.transient_periods * forcing_period;
      const double k =
          std::ceil((omega * after - job.phase) / (2.0 * std::numbers::pi) - 1e-9);
      const double t_section = (job.phase + 2.0 * std::numbers::pi * k) / omega;
      EventLog log(false);
      const auto transient = with_flow<System>(
          setup.method, stepper_settings(start_system, setup), [&](auto& stepper) {
            return simulate(start_system, stepper, initial_state, flight_mode, t0, t_section,
                            loop_options(setup), log);
          });
      request.start.assign(transient.state.begin(), transient.state.begin() + n);
      // (the impact section is built for one degree of freedom only, n = 2)
      if constexpr (n == 2) {
        if (job.impact_wall != 0) {
          // on the impact section: the transient's next impact with the wall
          const auto impact = first_wall_impact(
              start_system, transient.state, transient.mode, t_section,
              t_section + 20.0 * job.period * forcing_period, job.impact_wall, setup);
          if (!impact) return no_start(result, job, "no impact with the wall after the transient");
          request.start = {std::fmod(omega * impact->t, 2.0 * std::numbers::pi), impact->state[1]};
          wall_q = impact->state[0];
        }
      }
    }
    // the impact section: the wall's witness and the impacts with it per orbit
    [[maybe_unused]] std::size_t wall_witness_index = 0;
    [[maybe_unused]] int wall_impacts = 0;
    if constexpr (n == 2) {
      if (job.impact_wall != 0) {
        const auto witness =
            wall_witness(start_system, flight_mode, setup, job.impact_wall, request.start, wall_q);
        if (!witness)
          return no_start(result, job, "the start is not on the wall, moving into it");
        wall_witness_index = witness->first;
        wall_q = witness->second;
        wall_impacts = wall_impacts_per_orbit(start_system, flight_mode, setup, job.impact_wall,
                                              wall_witness_index, wall_q, request.start, job.period);
        if (wall_impacts == 0)
          return no_start(result, job, "no return to the wall within the orbit's period");
      }
    }
    // the section map of the system `base` describes, continued in job.parameter
    auto map_at = [&](const Scene& base, int period) {
      auto make_system = [base, parameter = job.parameter, system_at](double p) {
        Scene at = base;
        at.values[parameter] = p;
        return system_at(at);
      };
      if constexpr (n == 2) {
        if (job.impact_wall != 0)
          return impact_map_problem<System>(make_system, flight_mode, setup, job.impact_wall,
                                            wall_witness_index, wall_q, period,
                                            wall_impacts * period / job.period, omega);
      }
      return section_map_problem<System>(make_system, flight_mode, setup, job.phase, period,
                                         omega);
    };
    auto problem_for = [&](int period) {
      ContinuationProblem problem = map_at(scene, period);
      for (const SceneBoundary& boundary : boundaries)
        problem.boundaries.push_back(
            {boundary.type, boundary.note,
             [scene, parameter = job.parameter, value = boundary.value](double p) {
               Scene at = scene;
               at.values[parameter] = p;
               return value(at);
             }});
      return problem;
    };
    int period = job.period;
    result.branches.push_back({period, continue_branch(problem_for(period), request)});
    for (int doubling = 0; doubling < job.doublings; ++doubling) {
      const ContinuationResult& previous = result.branches.back().result;
      const auto found = std::find_if(
          previous.points.begin(), previous.points.end(),
          [](const BifurcationPoint& p) { return p.type == "period_doubling" && p.located; });
      if (found == previous.points.end()) break;
      const BifurcationPoint doubling_point = *found;
      // the monodromy of the n-fold map at the point, for the −1 eigenvector
      const ContinuationProblem problem = problem_for(period);
      const OrbitEvaluation at = problem.evaluate(doubling_point.state, doubling_point.parameter,
                                                  job.phase, false, {});
      std::vector<double> direction = eigenvector_for(at.monodromy, -1.0);
      direction.push_back(0.0);  // dp = 0
      period *= 2;
      ContinuationRequest doubled = request;
      doubled.from = doubling_point.parameter;
      result.branches.push_back(
          {period, continue_branch_from(problem_for(period), doubled, doubling_point.state,
                                        doubling_point.parameter, direction)});
    }
    // the impact phase reported in [0, 2π) (branches and curves run on it unreduced)
    const auto reduce = [&](OrbitPoint& state) {
      if (job.impact_wall == 0 || state.empty()) return;
      state[0] = std::fmod(state[0], 2.0 * std::numbers::pi);
      if (state[0] < 0.0) state[0] += 2.0 * std::numbers::pi;
    };
    for (ContinuedBranch& branch : result.branches) {
      for (BranchPoint& point : branch.result.branch) reduce(point.state);
      for (BifurcationPoint& point : branch.result.points) reduce(point.state);
    }
    if (!job.second_parameter.empty()) {
      result.has_curve =
          continue_curve_of<System>(result, 0, result.curve, result.curve_note, system_at, map_at,
                                    flight_mode, scene, job, setup, omega);
      for (CurvePoint& point : result.curve.curve) reduce(point.state);
      for (std::size_t b = 1; b < result.branches.size(); ++b) {
        BranchCurve doubled{static_cast<int>(b), result.branches[b].period};
        doubled.has_curve =
            continue_curve_of<System>(result, b, doubled.curve, doubled.note, system_at, map_at,
                                      flight_mode, scene, job, setup, omega);
        for (CurvePoint& point : doubled.curve.curve) reduce(point.state);
        result.doubled_curves.push_back(std::move(doubled));
      }
    }
    return result;
  }
}

}  // namespace impactlab
