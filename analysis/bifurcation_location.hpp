// The test functions of the bifurcations of a branch, and their detection
// and location between two points of it (branch_continuation.hpp):
//  * a fold (or branch point): det(M − I) = ∏ (λᵢ − 1) changes sign;
//  * a period doubling: det(M + I) = ∏ (λᵢ + 1) changes sign;
//  * a Neimark–Sacker point: det M − 1 (for N > 2: ∏ᵢ<ⱼ (λᵢλⱼ − 1))
//    changes sign with a complex pair of multipliers;
// each located by a root finder (TOMS 748) on the arclength between the two
// points, each trial point corrected onto the branch; a parameter boundary
// (ParameterBoundary) crossed, located at the root of its own function and
// the orbit corrected there; a change of the number of contact phases,
// located where a chatter lands in the contact phase as the onset of
// complete chatter (the root of the chatter's margin, chatter_onset.hpp),
// else at the root of the landing push (contact_landing.hpp) where both
// points land with pushes of opposite signs, otherwise (and a change of the
// stick impacts) by bisection on the arclength down to a bracket of 1e-10
// of the range in p.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <impactlab/analysis/branch_corrector.hpp>
#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/floquet_multipliers.hpp>

namespace impactlab {

// The test functions of a fold, det(M − I) = ∏ (λᵢ − 1), and of a period
// doubling, det(M + I) = ∏ (λᵢ + 1) (also the defining conditions of their
// two-parameter curves, curve_continuation.hpp).
double det_minus_identity(const MonodromyMatrix& m);
double det_plus_identity(const MonodromyMatrix& m);
// The test function of a Neimark–Sacker point: ∏ᵢ<ⱼ (λᵢλⱼ − 1), det M − 1
// for N = 2, zero where a complex pair crosses the unit circle whatever N
// (also the defining condition of its two-parameter curve).
double neimark_sacker_test(const MonodromyMatrix& m);

namespace detail {

// Internal to continuation: finds and locates the points between two
// consecutive nodes of a branch with the branch's own corrector.
template <int Size>
class BifurcationLocator {
 public:
  using Node = BranchNode<Size>;

  explicit BifurcationLocator(BranchCorrector<Size>& corrector) : corrector_(corrector) {}

  // Appends to `points` what lies between nodes a and b (b reached by the
  // arclength `step` from a): every test function's sign change, located
  // (or only detected where the request says not to locate), every
  // boundary crossed, and a change of the contact phases or of the stick
  // impacts per orbit.
  void detect(const Node& a, const Node& b, double step, std::vector<BifurcationPoint>& points);
  // Only the changes of the contact phases and of the stick impacts per
  // orbit: for a map whose monodromy is not the real map's (a stick forced
  // on the friction cone's edge, ContinuationProblem::stick_forced_at).
  void detect_count_changes(const Node& a, const Node& b, double step,
                            std::vector<BifurcationPoint>& points);

 private:
  using Vec = typename Spaces<Size>::Vec;
  using Correction = NodeCorrection<Size>;

  BifurcationPoint locate(BifurcationType type, double (*function)(const MonodromyMatrix&),
                          const Node& a, double step, double fa, double fb);
  // a count per orbit (contact phases, stick impacts) differs between a and b
  BifurcationPoint locate_count_change(int OrbitEvaluation::*count, const Node& a, const Node& b,
                                       double step);
  std::optional<BifurcationPoint> chatter_onset_from(const Vec& y0, const Vec& y1,
                                                     const std::string& what);
  std::optional<BifurcationPoint> locate_boundary(const ParameterBoundary& boundary,
                                                  const Node& a, const Node& b);

  BranchCorrector<Size>& corrector_;
};

extern template class BifurcationLocator<3>;
extern template class BifurcationLocator<Eigen::Dynamic>;

}  // namespace detail

}  // namespace impactlab
