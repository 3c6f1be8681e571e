// Two-parameter continuation: the curve of a fold, period doubling, grazing,
// Neimark–Sacker, contact onset or contact end point, or of a scene's
// parameter boundary (contact_boundary), in the plane of two parameters
// (p₁, p₂), followed by pseudo-arclength from a point located on a
// one-parameter branch (branch_continuation.hpp).
//
// Defining systems, each with the orbit condition F = Pⁿ(x; p₁, p₂) − x = 0:
//  * fold:             det(M − I) = 0       unknowns (q, q̇, p₁, p₂)
//  * period doubling:  det(M + I) = 0       unknowns (q, q̇, p₁, p₂)
//  * grazing:          gap(t_g) = 0 and gap rate(t_g) = 0, with the grazed
//                      wall's contacts suppressed near t_g (the virtual orbit
//                      through the graze, as the one-parameter driver solves
//                      it)                   unknowns (q, q̇, p₁, p₂, t_g)
//  * contact onset / end: the push into the wall on the mass at rest at the
//                      landing of the contact phase (contact_landing.hpp) is
//                      zero: the mass returns to the wall exactly where the
//                      push falls through zero, so the contact phase has
//                      zero length           unknowns (q, q̇, p₁, p₂)
//  * Neimark–Sacker:   ∏ᵢ<ⱼ(λᵢλⱼ − 1) = 0 (det M − 1 for N = 2)
//                                            unknowns (q, q̇, p₁, p₂)
//  * contact boundary: the scene's parameter boundary of that name is zero
//                      (the pendulum's V0·ω − g: ParameterBoundary,
//                      continuation_problem.hpp; the problem at each p₂
//                      carries it as a function of p₁)
//                                            unknowns (q, q̇, p₁, p₂)
// (q, q̇) stands for the N components of the state on the section (a model
// file's N states). M is the saltation-corrected monodromy; the other
// derivatives are central
// differences. Newton corrector with the arclength condition
// τ·(z − z_pred) = 0 in (q, q̇, p₁/|range₁|, p₂/|range₂| [, t_g/T]); the curve
// runs from p₂ = from₂ towards to₂ and ends there exactly, where p₁ leaves its
// range, where p₂ turns back past from₂, at the point limit, or where the
// corrector fails below the smallest step. A fold curve passes through a cusp
// (its tangent's parameter part reverses there) and reports it as a
// codimension-two point. A fold or period-doubling curve ends where its
// orbit's impact signature would change, at the point where it meets the
// grazing curve (its condition solved with the grazing system's).
#pragma once

#include <array>
#include <complex>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/continuation_problem.hpp>

namespace impactlab {

// The section map in two parameters: the one-parameter problem in p₁ at a
// fixed value of p₂.
struct TwoParameterProblem {
  std::function<ContinuationProblem(double p2)> at;
};

struct CurveRequest {
  CurveType type = CurveType::fold;
  double from1 = 0.0, to1 = 1.0;     // p₁'s range (the curve stops where p₁ leaves it)
  double from2 = 0.0, to2 = 1.0;     // p₂ runs from from2 towards to2
  double p1 = 0.0;                   // the start: a located point at p₂ = from2 (a guess; corrected)
  OrbitPoint state{};                // on the section ωt ≡ phase
  double graze_time = std::numeric_limits<double>::quiet_NaN();  // grazing: s since the section
  int graze_witness = -1;            // grazing: the touched wall's witness
  double initial_step = 0.0;         // arclength (0: 1/100)
  double min_step = 0.0;             // (0: 1e-7)
  double max_step = 0.0;             // (0: 1/50)
  int max_points = 5000;
  int max_newton_iterations = 12;
  double tolerance = 1e-11;          // |F| ≤ tolerance (1 + |x|)
  bool normal_forms = true;          // grazing: the normal form's kick signs watched at each point
};

CurveResult continue_curve(const TwoParameterProblem& problem, const CurveRequest& request);

}  // namespace impactlab
