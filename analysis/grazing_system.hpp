// The grazing extended system of a branch (branch_continuation.hpp): where a
// flight extremum of a wall gap reaches the wall or an impact velocity goes
// to zero, the impact signature changes and the branch ends at the grazing
// point, solved in (x, p, t_g): F = Pⁿ(x; p) − x = 0 with the wall's contacts
// near t_g suppressed (the virtual orbit that passes through the graze),
// gap(t_g) = 0 and gap rate(t_g) = 0, by Newton with a central-difference
// Jacobian. On the impact section, a grazing of the section's own impact
// (where that map ends) is solved by the same system on the stroboscopic map
// of the same system (ContinuationProblem::strobe) and carried back onto the
// section.
#pragma once

#include <optional>
#include <vector>

#include <impactlab/analysis/branch_corrector.hpp>
#include <impactlab/analysis/continuation.hpp>

namespace impactlab::detail {

// Internal to continuation: the grazing points within reach of the last
// nodes of a branch, with the branch's own corrector (its coordinates, its
// working section and its count of map evaluations).
template <int Size>
class GrazingSystem {
 public:
  using Node = BranchNode<Size>;

  explicit GrazingSystem(BranchCorrector<Size>& corrector) : corrector_(corrector) {}

  // A gap or impact speed of the last node that, extrapolated linearly from
  // the last two nodes, vanishes within the next step h: end at the grazing
  // point before Newton meets the square-root singularity.
  static bool grazing_ahead(const std::vector<Node>& nodes, double h);

  // After a failed step of length h from the last node: the grazing system
  // solved for each candidate (the lowest flight gap, the slowest impact,
  // whose value vanishes within a few failed steps), the solution nearest
  // along the branch and within reach; none where no candidate gives one.
  std::optional<BifurcationPoint> grazing_within_reach(const std::vector<Node>& nodes, double h);

 private:
  using Vec = typename Spaces<Size>::Vec;
  using Extended = typename Spaces<Size>::Extended;

  // A solution of the grazing system: z = (x, p, t_g) in branch units, the
  // orbit there, and Newton's last step in p (branch units).
  struct Solution {
    Extended z;
    OrbitEvaluation orbit;
    double parameter_step = 0.0;
    ContactWindow window;  // the contacts suppressed (times since the section)
  };
  // A located grazing point and where it lies in branch units (x, p).
  struct Located {
    BifurcationPoint point;
    Vec y;
  };

  std::optional<Solution> newton(const ContinuationProblem& on, double phase, Extended z,
                                 int witness);
  BifurcationPoint grazing_point(const Solution& solved, int witness) const;
  std::optional<GrazingNormalForm> normal_form_of(const ContinuationProblem& on, double phase,
                                                  const Solution& solved, int witness) const;
  std::optional<Located> solve(const Node& last, int witness, double time, double h);
  std::optional<Located> solve_section_wall(const Node& last);

  BranchCorrector<Size>& corrector_;
};

extern template class GrazingSystem<3>;
extern template class GrazingSystem<Eigen::Dynamic>;

}  // namespace impactlab::detail
