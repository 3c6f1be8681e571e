// `continue --all`: every orbit of the period that `periodic --all` finds at
// the start of the parameter's range (api/periodic_job.hpp: deflated Newton
// shooting from starts drawn from a box), each continued along the parameter
// (continue_orbit, api/scene_jobs.hpp), so that branches not connected to
// the scene's own attractor (isolas, the other side of a fold) appear on the
// diagram beside it.
#pragma once

#include <string>
#include <vector>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/api/continuation_job.hpp>
#include <impactlab/api/periodic_job.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

struct EveryOrbitContinuation {
  PeriodicOrbitsJobResult orbits;      // found at parameter = from
  ContinuationJobResult continuation;  // every orbit's branches, one after another
  std::vector<int> branch_orbit;       // per branch: the id of the orbit it continues
  std::vector<std::string> not_continued;  // per orbit not continued: why
};

// The orbits of `search` (its period, phase, starts, box, seed) at
// job.parameter = job.from, each continued as `job` continues one, from its
// point on the section with its minimal period. An orbit that lies on a branch
// already continued (the other one of a fold's pair) is not continued again
// (`not_continued` says on whose). Throws BadInput: `all` with `param2` or an impact section,
// and periodic --all's (no orbit: key `starts`).
EveryOrbitContinuation continue_every_orbit(const Scene& scene, const ContinuationJob& job,
                                            const PeriodicJob& search);

// The same with the search of `options` (its starts, box and seed): the
// CLI's and Python's `continue --all`.
EveryOrbitContinuation continue_every_orbit(const Scene& scene, const ContinuationJob& job,
                                            const ContinueOptions& options);

}  // namespace impactlab
