// The n-fold stroboscopic map of a concrete system with Jacobians as a
// ContinuationProblem (continuation_problem.hpp): Pⁿ(x; p) from the section
// ωt ≡ phase, its saltation-corrected monodromy, the impact signature, the
// slowest impact and the lowest flight gap (sampled), the gap along the
// orbit with one wall's contacts suppressed near a time (the virtual orbit
// of a grazing point's extended system), and the transport of a state from
// one section phase to another.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>

#include <impactlab/analysis/chatter_onset.hpp>
#include <impactlab/analysis/contact_landing.hpp>
#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/decorated_system.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/grazing_local_flow.hpp>
#include <impactlab/analysis/map_evaluation.hpp>
#include <impactlab/analysis/variational.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>

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

// The system at a value of the continued parameter. A function, not a
// template parameter: each caller's lambda would compile the map problems
// (and their grazing data) again for the same system.
template <class System>
using SystemOfParameter = std::function<System(double)>;

// The problem for p ↦ make_system(p) (forcing_omega_of gives its forcing
// frequency), section ωt ≡ phase, period n, from flight mode.
template <HasJacobian System>
ContinuationProblem stroboscopic_map_problem(SystemOfParameter<System> make_system,
                                             typename System::Mode flight_mode,
                                             const FlowSetup& setup, double phase, int period,
                                             double forcing_omega_at_start) {
  using Mode = typename System::Mode;
  using Wrapped = DecoratedSystem<System>;
  using Tangent = Variational<Wrapped>;
  constexpr std::size_t n = tangent_dimension_of<System>;  // the OrbitPoint's components
  constexpr int samples_per_period = 96;
  struct Shared {
    SystemOfParameter<System> make_system;
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
    result.one_sided = run.counters.one_sided_events > 0;
    result.one_sided_witness = trace.one_sided_witness;
    const auto state = Tangent::base_state(run.state);
    result.completed = std::all_of(state.begin(), state.begin() + n,
                                   [](double component) { return std::isfinite(component); });
    result.image.assign(state.begin(), state.begin() + n);
    for (const auto& row : Tangent::fundamental_matrix(run.state))
      result.monodromy.emplace_back(row.begin(), row.end());
    result.span = span;
    result.omega = omega;
    note_events(log.records().begin(), log.records().end(), t0, result);
    for (const EventRecord& record : log.records())
      if (record.kind == EventKind::impact && record.sticks)
        for (const auto& crossing : trace.crossings)
          if (crossing.t == record.t) result.stuck_witness = crossing.witness;
    note_landing_push(system, log.records().begin(), log.records().end(), t0, result);
    note_chatter_margin(system, log.records().begin(), log.records().end(), t0 + 2.0 * span,
                        result);
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
  problem.grazing_flow = grazing_local_flow_function<System>(
      make_system, [](const System& system) { return forcing_omega_of(system); }, flight_mode,
      setup, period);
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

}  // namespace impactlab
