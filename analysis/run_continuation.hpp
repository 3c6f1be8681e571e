// A continuation from a scene for a concrete system (continuation_of_scene,
// api/system_jobs.hpp): the start from a transient (or the job's start), on
// the stroboscopic or the impact section, the branch, the period-doubling
// cascade, and the two-parameter curves (continuation.hpp's request and
// result).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include <impactlab/analysis/branch_continuation.hpp>
#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/curve_from_branch.hpp>
#include <impactlab/analysis/flow_setup.hpp>
#include <impactlab/analysis/floquet_multipliers.hpp>
#include <impactlab/analysis/impact_map_problem.hpp>
#include <impactlab/analysis/neutral_component.hpp>
#include <impactlab/analysis/scene_boundary.hpp>
#include <impactlab/analysis/stroboscopic_map_problem.hpp>
#include <impactlab/core/has_jacobian.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene.hpp>
#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>

namespace impactlab {

// A job whose start was not found: one branch stopped at its start, with why.
inline ContinuationJobResult no_start(ContinuationJobResult& result, const ContinuationJob& job,
                                      const std::string& why) {
  ContinuationResult stopped;
  stopped.stop_reason = StopReason::start_not_converged;
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
    double wall_q = 0.0;  // the impact section: q on the wall at the start (a guess)
    ContinuationRequest request = job.numerics;
    request.from = job.from;
    request.to = job.to;
    constexpr std::size_t n = tangent_dimension_of<System>;
    result.dimension = n;
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
      // the section map runs from a flight: an orbit resting on a wall at
      // the section (the ball riding its table) needs another section phase
      if (job.impact_wall == 0 && transient.mode != flight_mode)
        return no_start(result, job,
                        fmt::format("the transient rests on a wall at the section (omega t "
                                    "= {:g} rad): try a `section` strobe:PHASE in a flight",
                                    job.phase));
      if (job.impact_wall != 0) {
        // on the impact section: the transient's next impact with the wall,
        // (phase, the state before it without q)
        const auto impact = first_wall_impact(start_system, transient.state, transient.mode,
                                              t_section,
                                              t_section + 20.0 * job.period * forcing_period,
                                              job.impact_wall, setup);
        if (!impact) return no_start(result, job, "no impact with the wall after the transient");
        request.start = impact->state;
        request.start[0] = std::fmod(omega * impact->t, 2.0 * std::numbers::pi);
        wall_q = impact->state[0];
      }
    }
    // the impact section: the wall's witness and the impacts with it per orbit
    std::size_t wall_witness_index = 0;
    int wall_impacts = 0;
    if (job.impact_wall != 0) {
      const auto witness =
          wall_witness(start_system, flight_mode, setup, job.impact_wall, request.start, wall_q);
      if (!witness) return no_start(result, job, "the start is not on the wall, moving into it");
      wall_witness_index = witness->first;
      wall_q = witness->second;
      wall_impacts = wall_impacts_per_orbit(start_system, flight_mode, setup, job.impact_wall,
                                            wall_witness_index, wall_q, request.start, job.period);
      if (wall_impacts == 0)
        return no_start(result, job, "no return to the wall within the orbit's period");
    }
    // a component along which the map is neutral (neutral_component.hpp) is
    // held at its start value (the free ball's spin where every impact
    // slides); a one-degree-of-freedom orbit has none
    std::optional<HeldComponent> held;
    // the section map of the system `base` describes, continued in
    // job.parameter, integrated with `flow` (the scene's setup unless said)
    // (with every impact at the wall of flight witness `forced_witness`
    // forced to stick, where that is not −1: ContinuationProblem::stick_forced_at)
    auto full_map_at = [&](const Scene& base, int period, const FlowSetup* flow = nullptr,
                           int forced_witness = -1) {
      auto make_system = [=, parameter = job.parameter](double p) {
        Scene at = base;
        at.values[parameter] = p;
        System system = system_at(at);
        if constexpr (requires { system.force_stick_at_witness(std::size_t{0}); })
          if (forced_witness >= 0)
            system.force_stick_at_witness(static_cast<std::size_t>(forced_witness));
        return system;
      };
      const FlowSetup& integration = flow != nullptr ? *flow : setup;
      if (job.impact_wall != 0)
        return impact_map_problem<System>(make_system, flight_mode, integration, job.impact_wall,
                                          wall_witness_index, wall_q, period,
                                          wall_impacts * period / job.period, omega);
      return stroboscopic_map_problem<System>(make_system, flight_mode, integration, job.phase,
                                              period, omega);
    };
    auto map_at = [&](const Scene& base, int period) {
      if (!held) return full_map_at(base, period);
      return with_component_held(full_map_at(base, period), *held);
    };
    // hold the component along which the map is neutral at `start`, if any
    auto hold_if_neutral = [&](const OrbitPoint& start) {
      request.start = start;
      if constexpr (n > 2) {
        const OrbitEvaluation at =
            full_map_at(scene, job.period).evaluate(start, job.from, job.phase, false, {});
        if (at.completed) {
          if (const auto component = neutral_component(at.monodromy)) {
            held = HeldComponent{*component, start[*component]};
            request.start = without_held_component(start, *held);
            result.neutral = held;
          }
        }
      }
    };
    const OrbitPoint full_start = request.start;
    hold_if_neutral(full_start);
    // the section map with the scene's boundaries, as functions of the
    // continued parameter at the other values of `base`
    auto bounded_map_at = [&](const Scene& base, int period) {
      ContinuationProblem problem = map_at(base, period);
      if constexpr (requires(System& system) { system.force_stick_at_witness(std::size_t{0}); })
        if (!held && job.impact_wall == 0)
          problem.stick_forced_at = [&full_map_at, base, period,
                                     walls = start_system.witness_count(flight_mode)](
                                        int witness) -> std::shared_ptr<const ContinuationProblem> {
            if (witness < 0 || static_cast<std::size_t>(witness) >= walls) return nullptr;
            return std::make_shared<const ContinuationProblem>(
                full_map_at(base, period, nullptr, witness));
          };
      for (const SceneBoundary& boundary : boundaries)
        problem.boundaries.push_back(
            {boundary.name, boundary.note,
             [base, parameter = job.parameter, value = boundary.value](double p) {
               Scene at = base;
               at.values[parameter] = p;
               return value(at);
             }});
      return problem;
    };
    auto problem_for = [&](int period) { return bounded_map_at(scene, period); };
    // a held component checked on the full map at every point of a branch
    auto checked = [&](ContinuationResult branch, int period) {
      if (held) {
        FlowSetup tighter = setup;
        tighter.rtol /= 100.0;
        tighter.atol /= 100.0;
        end_where_held_component_drifts(branch, full_map_at(scene, period),
                                        full_map_at(scene, period, &tighter), *held,
                                        request.tolerance);
      }
      return branch;
    };
    int period = job.period;
    ContinuationResult first = checked(continue_branch(problem_for(period), request), period);
    if (held && first.stop_reason == StopReason::neutral_drift && first.branch.empty()) {
      // the start was on no family: the map looked neutral there, but the
      // held component drifts at once (a transient that ended before the
      // orbit's sticking impacts set in). Newton converges the start on the
      // full map, the neutral component is looked for again on that orbit,
      // and the branch runs from it
      held.reset();
      result.neutral.reset();
      ContinuationRequest converge = request;
      converge.start = full_start;
      converge.max_points = 1;
      const ContinuationResult converged = continue_branch(problem_for(period), converge);
      if (!converged.branch.empty()) {
        hold_if_neutral(converged.branch.front().state);
        first = checked(continue_branch(problem_for(period), request), period);
      } else {
        first = converged;
      }
    }
    result.branches.push_back({period, std::move(first)});
    for (int doubling = 0; doubling < job.doublings; ++doubling) {
      const ContinuationResult& previous = result.branches.back().result;
      const auto found = std::find_if(
          previous.points.begin(), previous.points.end(),
          [](const BifurcationPoint& p) {
            return p.type == BifurcationType::period_doubling && p.located;
          });
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
          {period, checked(continue_branch_from(problem_for(period), doubled, doubling_point.state,
                                                doubling_point.parameter, direction),
                           period)});
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
          continue_curve_of<System>(result, 0, result.curve, result.curve_note, system_at,
                                    bounded_map_at, flight_mode, scene, job, setup, omega);
      for (CurvePoint& point : result.curve.curve) reduce(point.state);
      for (std::size_t b = 1; b < result.branches.size(); ++b) {
        BranchCurve doubled{static_cast<int>(b), result.branches[b].period};
        doubled.has_curve =
            continue_curve_of<System>(result, b, doubled.curve, doubled.note, system_at,
                                      bounded_map_at, flight_mode, scene, job, setup, omega);
        for (CurvePoint& point : doubled.curve.curve) reduce(point.state);
        result.doubled_curves.push_back(std::move(doubled));
      }
      if (job.doublings > 0 && result.has_curve)
        for (const CodimensionTwoPoint& point : result.curve.points) {
          const std::optional<CurveType> through = curve_through(point.type, result.curve.type);
          if (!point.located || !through) continue;
          BranchCurve switched{0, job.period};
          switched.started_at = point.type;
          switched.has_curve = continue_curve_from_point(
              point, *through, job.period, switched.curve, switched.note, map_at, scene, job);
          result.switched_curves.push_back(std::move(switched));
        }
    }
    if (held) restore_held_component(result, *held);
    return result;
  }
}

}  // namespace impactlab
