// A component of the section state along which the section map is neutral:
// perturbing it changes nothing else and it passes through unchanged
// (the monodromy's column is the unit vector). Its multiplier is 1 exactly
// and the orbits form a family along it: the free spin of a ball whose
// impacts all slide, which then decides only the slip's sign.
//
// Continuation cannot run on a family (the map's Jacobian loses rank, and the
// corrector walks along the family instead of the parameter), so the
// component is held at its start value and the branch is followed in the
// others; every state and multiplier list reported has the component and its
// multiplier 1 back. The component's own residual, its drift over the orbit,
// does not depend on its value: where it is not zero, the motion is periodic
// in the other components only (the spin drifts) and there is no periodic
// orbit. Each point of a branch is checked on the full map once it is found,
// and the branch ends at the first that drifts (StopReason::neutral_drift).
#pragma once

#include <complex>
#include <cstddef>
#include <optional>
#include <vector>

#include <impactlab/analysis/continuation_problem.hpp>

namespace impactlab {

// The first component whose monodromy column is the unit vector to
// `tolerance` (absolute: the monodromy is dimensionless per component pair
// only where the units agree; the spin's column has a 1 and exact zeros).
std::optional<std::size_t> neutral_component(const MonodromyMatrix& monodromy,
                                             double tolerance = 1e-12);

// The problem on the other components, `held` fixed.
ContinuationProblem with_component_held(const ContinuationProblem& full, const HeldComponent& held);

// The branch ended at its first point whose held component does not return
// on the full map (points of the reduced problem; the located points past it
// dropped too). The drift is the orbit's own: the evaluated one less what
// the other components' residual error moves it by through the monodromy
// (one Newton step). It counts where it exceeds tolerance (1 + |x_c|) plus
// tolerance (1 + |x|) through the monodromy's row, and only if `tighter`,
// the same map integrated at a hundredth of the tolerances, drifts by at
// least half as much: a drift that shrinks with the integrator's tolerance
// is its error, not the orbit's. Where the free ball's spin is held, each
// impact's error in θ̇⁻ reaches the spin amplified by the impulse's lever
// r/I_b, so the integrator's error alone can exceed the bound (jin2003 at
// V0 = 4, r = 0.02 m, rtol 1e-10: 1.5e-7 rad/s per 6 periods).
void end_where_held_component_drifts(ContinuationResult& branch, const ContinuationProblem& full,
                                     const ContinuationProblem& tighter, const HeldComponent& held,
                                     double tolerance);

// every state of a job's result with the held component back in place, and
// every multiplier list with the neutral multiplier
void restore_held_component(ContinuationJobResult& result, const HeldComponent& held);

// a state of the held problem with the held component back in place
OrbitPoint with_held_component(const OrbitPoint& reduced, const HeldComponent& held);
// a state of the full problem without the held component
OrbitPoint without_held_component(const OrbitPoint& full, const HeldComponent& held);
// the multipliers of the held problem with the neutral one (1) back, largest modulus first
std::vector<std::complex<double>> with_neutral_multiplier(std::vector<std::complex<double>> multipliers);

}  // namespace impactlab
