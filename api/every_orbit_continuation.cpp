#include <impactlab/api/every_orbit_continuation.hpp>

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <impactlab/api/job_options.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

// Whether `point` (on the section at parameter = from) lies on `branch`: the
// branch crosses `from` between two of its points, and the state linearly
// interpolated there is within a quarter of their chord of `point` (the
// interpolation's error is second order in the chord).
bool on_branch(const ContinuationResult& branch, double from, const std::vector<double>& point,
               std::size_t dimension) {
  const auto& points = branch.branch;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double a = points[i].parameter - from, b = points[i + 1].parameter - from;
    if (a * b > 0.0 || a == b) continue;
    const double fraction = a / (a - b);
    double miss = 0.0, chord = 0.0, size = 0.0;
    for (std::size_t k = 0; k < dimension; ++k) {
      const double p = points[i].state[k], q = points[i + 1].state[k];
      const double between = p + fraction * (q - p);
      miss += (between - point[k]) * (between - point[k]);
      chord += (q - p) * (q - p);
      size += point[k] * point[k];
    }
    if (std::sqrt(miss) <= 0.25 * std::sqrt(chord) + 1e-9 * (1.0 + std::sqrt(size))) return true;
  }
  return false;
}

}  // namespace

EveryOrbitContinuation continue_every_orbit(const Scene& scene, const ContinuationJob& job,
                                            const PeriodicJob& search) {
  if (!job.second_parameter.empty())
    throw BadInput("param2", job.second_parameter,
                   fmt::format("cannot be given with {}: one curve per run", mention("all")));
  if (job.impact_wall != 0)
    throw BadInput("section", fmt::format("impact:{}", job.impact_wall),
                   fmt::format("{} finds orbits on the stroboscopic section: give strobe[:PHASE]",
                               mention("all")));
  EveryOrbitContinuation out;
  Scene at_start = scene;
  at_start.values[job.parameter] = job.from;
  PeriodicJob orbits_job = search;
  orbits_job.all = true;
  orbits_job.period = std::to_string(job.period);
  orbits_job.phase = job.phase;
  out.orbits = find_periodic_orbits(at_start, orbits_job);
  const std::size_t dimension = out.orbits.result.tangent_dimension;
  for (const FoundPeriodicOrbit& orbit : out.orbits.result.orbits) {
    // an orbit on a branch already continued (the other one of a fold's pair)
    const auto& so_far = out.continuation.branches;
    const auto known = std::find_if(so_far.begin(), so_far.end(), [&](const ContinuedBranch& b) {
      return on_branch(b.result, job.from, orbit.state, dimension);
    });
    if (known != so_far.end()) {
      out.not_continued.push_back(
          fmt::format("orbit {}: on the branch of orbit {}", orbit.id,
                      out.branch_orbit[static_cast<std::size_t>(known - so_far.begin())]));
      continue;
    }
    ContinuationJob from_orbit = job;
    from_orbit.has_start = true;
    from_orbit.start.assign(orbit.state.begin(), orbit.state.begin() + dimension);
    from_orbit.period = orbit.minimal_period;
    try {
      ContinuationJobResult continued = continue_orbit(scene, from_orbit);
      out.continuation.available = continued.available;
      out.continuation.dimension = continued.dimension;
      if (!out.continuation.neutral) out.continuation.neutral = continued.neutral;
      for (ContinuedBranch& branch : continued.branches) {
        out.continuation.branches.push_back(std::move(branch));
        out.branch_orbit.push_back(orbit.id);
      }
    } catch (const BadInput& bad) {
      out.not_continued.push_back(fmt::format("orbit {}: {}", orbit.id, bad.what()));
    }
  }
  if (out.continuation.branches.empty())
    throw BadInput("param", fmt::format("{}={}:{}", job.parameter, job.from, job.to),
                   fmt::format("none of the {} orbits found by {} could be continued",
                               out.orbits.result.orbits.size(), mention("all")));
  return out;
}

EveryOrbitContinuation continue_every_orbit(const Scene& scene, const ContinuationJob& job,
                                            const ContinueOptions& options) {
  PeriodicJob search;
  search.starts = options.starts;
  search.box = options.box;
  search.seed = options.seed;
  return continue_every_orbit(scene, job, search);
}

}  // namespace impactlab
