// Pseudo-arclength continuation of one branch of a period-n orbit, a fixed
// point of the section map of a ContinuationProblem (continuation_problem.hpp),
// with its bifurcations and grazing points located on the way
// (docs/analysis.md, "Continuation"). The driver knows no oscillator:
//  * unknowns y = (x, p), equations F(x, p) = Pⁿ(x; p) − x = 0 and the
//    arclength condition (branch_corrector.hpp);
//  * the step grows after easy corrections and is halved where Newton fails,
//    where the tangent turns by more than 30°, or where the impact signature
//    (the walls hit, in order) changes; the branch stops below the smallest
//    step; a contact phase appearing or ending alone does not stop it;
//  * between two points, sign changes of the test functions, boundaries
//    crossed and changes of the contact phases are located
//    (bifurcation_location.hpp);
//  * where the signature changes, the branch ends at the grazing point
//    (grazing_system.hpp);
//  * a stroboscopic section is moved off an impact that comes within 2 % of
//    the span of it (where the map jumps); states are reported on the
//    requested section.
#pragma once

#include <vector>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/continuation_problem.hpp>

namespace impactlab {

// Corrects `request.start` onto the orbit at p = from (Newton at fixed p) and
// continues the branch towards `to`.
ContinuationResult continue_branch(const ContinuationProblem& problem,
                                   const ContinuationRequest& request);

// Starts a branch from a point (x, p) along a given direction (dx, dp) of
// unit size instead of the branch's own tangent: the branch switch at a
// period doubling (the doubled orbit leaves along the −1 eigenvector, dp = 0).
// direction: N + 1 components.
ContinuationResult continue_branch_from(const ContinuationProblem& problem,
                                        const ContinuationRequest& request,
                                        const OrbitPoint& x, double p,
                                        const std::vector<double>& direction);

}  // namespace impactlab
