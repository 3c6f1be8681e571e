// Every periodic orbit of period n from many starts, for any oscillator with
// Jacobians (api/system_jobs.hpp's periodic_orbits_of_scene): each start is
// run from t0 to the first section time at or after it, then Newton shooting
// (analysis/floquet.hpp) deflated by every section point of the orbits found
// before (analysis/deflation.hpp). A converged point is checked against the
// known points once more (deflation makes a known root repulsive, not
// unreachable); a new one is followed around its orbit for its minimal
// period, its points, its impacts and its Floquet multipliers.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <utility>
#include <vector>

#include <impactlab/analysis/deflation.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/analysis/periodic_orbits.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/core/state_names.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

template <HybridSystem System>
PeriodicOrbitsResult run_periodic_orbits(const System& system,
                                         const std::vector<typename System::State>& starts,
                                         typename System::Mode mode0, const Scene& scene,
                                         const PeriodicOrbitsRequest& request, double omega) {
  PeriodicOrbitsResult result;
  if constexpr (!HasJacobian<System>) {
    result.note = "this oscillator/model has no Jacobians";
    return result;
  } else {
    using State = typename System::State;
    constexpr std::size_t n = tangent_dimension_of<System>;
    result.available = true;
    result.state_names = state_names_of(system);
    result.tangent_dimension = n;
    const FlowSetup setup = flow_setup(scene);
    SectionRequest size;  // one orbit from each start, sized like a section run
    size.transient_periods = request.period + 1;
    size.points = 0;
    check_section_size(size, omega, system.max_step(), setup.step_budget);
    const double period = 2.0 * std::numbers::pi / omega;
    result.forcing_period = period;
    const double t0 = scene.number("t0");
    // the first section time at or after t0
    const double turns = std::ceil((omega * t0 - request.phase) / (2.0 * std::numbers::pi) - 1e-9);
    const double t_section = (request.phase + 2.0 * std::numbers::pi * turns) / omega;
    result.t_section = t_section;
    const double span = request.period * period;

    // |x − y| ≤ tolerance (1 + |y|) on the tangent space
    const auto same_point = [&](const TangentVectorOf<n>& x, const TangentVectorOf<n>& y) {
      TangentVectorOf<n> d;
      for (std::size_t i = 0; i < n; ++i) d[i] = x[i] - y[i];
      return tangent_norm<n>(d) <= request.distinct_tolerance * (1.0 + tangent_norm<n>(y));
    };
    Deflation deflation;
    // every section point found, with its orbit's id
    std::vector<std::pair<TangentVectorOf<n>, int>> known;

    using Tangent = TangentOf<System>;
    const Tangent tangent{DecoratedSystem<System>(system)};
    with_flow<Tangent>(setup.method, stepper_settings(tangent, setup), [&](auto& stepper) {
      for (int s = 0; s < static_cast<int>(starts.size()); ++s) {
        if (request.progress && s > 0) request.progress(static_cast<double>(s) / starts.size());
        State x = starts[s];
        typename System::Mode mode = mode0;
        if (t_section > t0) {
          const auto to_section =
              flow_with_jacobian(tangent, stepper, setup, x, mode, t0, t_section);
          if (to_section.termination != Termination::completed) {
            result.start_outcomes.push_back(StartOutcome::stopped);
            result.start_orbit.push_back(0);
            continue;
          }
          x = to_section.state;
          mode = to_section.mode;
        }
        const auto orbit =
            locate_periodic_orbit(tangent, stepper, setup, x, mode, t_section, span,
                                  request.max_iterations, request.tolerance,
                                  request.deflate ? &deflation : nullptr);
        if (!orbit.converged) {
          const bool stopped = orbit.termination != Termination::completed &&
                               orbit.termination != Termination::no_tangent_map;
          result.start_outcomes.push_back(stopped ? StartOutcome::stopped
                                                  : StartOutcome::not_converged);
          result.start_orbit.push_back(0);
          continue;
        }
        const TangentVectorOf<n> point = tangent_part<n>(orbit.state);
        const auto match =
            std::find_if(known.begin(), known.end(),
                         [&](const auto& entry) { return same_point(point, entry.first); });
        if (match != known.end()) {
          result.start_outcomes.push_back(StartOutcome::known_orbit);
          result.start_orbit.push_back(match->second);
          continue;
        }
        // around the orbit one forcing period at a time: its points up to
        // the first return (the minimal period k, a divisor of n)
        std::vector<TangentVectorOf<n>> points{point};
        State iterate = orbit.state;
        typename System::Mode iterate_mode = orbit.mode;
        int minimal_period = request.period;
        for (int j = 1; j < request.period; ++j) {
          const auto step = flow_with_jacobian(tangent, stepper, setup, iterate, iterate_mode,
                                               t_section + (j - 1) * period,
                                               t_section + j * period);
          iterate = step.state;
          iterate_mode = step.mode;
          const TangentVectorOf<n> next = tangent_part<n>(iterate);
          if (request.period % j == 0 && same_point(next, point)) {
            minimal_period = j;
            break;
          }
          points.push_back(next);
        }
        // the orbit's own map Pᵏ: its monodromy, multipliers and events
        const auto cycle = flow_with_jacobian(tangent, stepper, setup, orbit.state, orbit.mode,
                                              t_section, t_section + minimal_period * period);
        FoundPeriodicOrbit found;
        found.id = static_cast<int>(result.orbits.size()) + 1;
        found.minimal_period = minimal_period;
        found.start = s;
        found.state.assign(orbit.state.begin(), orbit.state.end());
        found.mode = static_cast<int>(orbit.mode);
        found.impacts = cycle.impacts;
        found.contact_phases = cycle.contact_phases;
        found.iterations = orbit.iterations;
        found.residual = orbit.residual;
        found.termination = cycle.one_sided ? Termination::no_tangent_map : cycle.termination;
        if (found.termination == Termination::completed) {
          const auto multipliers = eigenvalues<n>(cycle.jacobian);
          found.multipliers.assign(multipliers.begin(), multipliers.end());
        } else {
          found.multipliers.assign(n, std::complex<double>(std::nan(""), std::nan("")));
        }
        found.stable = std::all_of(found.multipliers.begin(), found.multipliers.end(),
                                   [](std::complex<double> z) { return std::abs(z) < 1.0; });
        for (const auto& p : points) {
          known.emplace_back(p, found.id);
          deflation.roots.emplace_back(p.begin(), p.end());
        }
        result.orbits.push_back(std::move(found));
        result.start_outcomes.push_back(StartOutcome::new_orbit);
        result.start_orbit.push_back(result.orbits.back().id);
      }
      return 0;
    });
    return result;
  }
}

}  // namespace impactlab
