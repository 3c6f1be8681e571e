// Holding a neutral component of a continuation (analysis/neutral_component.hpp)
// on a map whose fixed points and drift are known in closed form:
//     P(x; p) = (x0 / 2 + p, x1 + d(p)),  d(p) = 0 for p <= 1/2, (p − 1/2)² above
// Its monodromy [[1/2, 0], [0, 1]] has the unit column of component 1: the
// fixed points form the family (2p, any x1) while d(p) = 0, and there are
// none past p = 1/2, where component 1 drifts. An integration error is
// modelled as a constant added to d, which a tighter integration divides.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include <impactlab/analysis/branch_continuation.hpp>
#include <impactlab/analysis/neutral_component.hpp>

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

double drift(double p) { return p <= 0.5 ? 0.0 : (p - 0.5) * (p - 0.5); }

ContinuationProblem drifting_family(double integration_error = 0.0) {
  ContinuationProblem problem;
  problem.phase = 0.0;
  problem.forcing_period_at_p = 2.0 * M_PI;
  problem.evaluate = [integration_error](const OrbitPoint& x, double p, double, bool,
                                         const ContactWindow&) {
    OrbitEvaluation e;
    e.completed = true;
    e.image = {0.5 * x[0] + p, x[1] + drift(p) + integration_error};
    e.monodromy = {{0.5, 0.0}, {0.0, 1.0}};
    e.span = 2.0 * M_PI;
    e.omega = 1.0;
    return e;
  };
  problem.gap_at = [](const OrbitPoint&, double, double, const ContactWindow&, double) {
    return GapSample{};
  };
  problem.transport = [](const OrbitPoint& x, double, double, double) {
    return std::optional<OrbitPoint>(x);
  };
  return problem;
}

// the column, not the row: the held component's image may depend on the
// others (the spin's change over an orbit depends on θ and θ̇)
TEST(NeutralComponent, FoundOnlyWhereTheColumnIsTheUnitVector) {
  EXPECT_EQ(neutral_component({{0.5, 0.0}, {0.0, 1.0}}), 1u);
  EXPECT_EQ(neutral_component({{0.5, 0.0}, {1e-3, 1.0}}), 1u);
  EXPECT_EQ(neutral_component({{0.5, 0.0}, {0.0, 1.0 + 1e-9}}), std::nullopt);
  EXPECT_EQ(neutral_component({{0.5, 1e-3}, {0.0, 1.0}}), std::nullopt);
  EXPECT_EQ(neutral_component({{0.5, 0.2}, {0.3, 0.9}}), std::nullopt);
}

TEST(NeutralComponent, HeldBranchEndsWhereTheComponentDrifts) {
  const ContinuationProblem full = drifting_family();
  const HeldComponent held{1, 3.0};
  ContinuationRequest request;
  request.from = 0.0;
  request.to = 1.0;
  request.start = {0.1};  // the other component only; Newton finds 2p
  ContinuationResult branch = continue_branch(with_component_held(full, held), request);
  ASSERT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  const double last_before = branch.branch.back().parameter;
  EXPECT_NEAR(last_before, 1.0, 1e-12);
  // the drift is the orbit's: a tighter integration gives the same
  end_where_held_component_drifts(branch, full, full, held, request.tolerance);
  EXPECT_EQ(branch.stop_reason, StopReason::neutral_drift);
  ASSERT_FALSE(branch.branch.empty());
  for (const BranchPoint& point : branch.branch) {
    // kept: the drift within the tolerance (1 + 3) + the row's zero sensitivity
    EXPECT_LE(drift(point.parameter), request.tolerance * 4.0) << point.parameter;
    EXPECT_NEAR(point.state[0], 2.0 * point.parameter, 1e-9);
  }
  // and the branch has gone as far as the drift allows, to one step
  EXPECT_GT(branch.branch.back().parameter, 0.5 - 0.05);

  ContinuationJobResult job;
  job.dimension = 2;
  job.branches.push_back({1, branch});
  restore_held_component(job, held);
  for (const BranchPoint& point : job.branches[0].result.branch) {
    ASSERT_EQ(point.state.size(), 2u);
    EXPECT_EQ(point.state[1], 3.0);
    ASSERT_EQ(point.multipliers.size(), 2u);
    EXPECT_EQ(point.multipliers[0], std::complex<double>(1.0, 0.0));
    EXPECT_NEAR(point.multipliers[1].real(), 0.5, 1e-12);
  }
}

// A drift a hundred times the bound at every point ends the branch at its
// first point, unless the tighter integration takes it down to a hundredth:
// then it is the integrator's error, and the branch is kept whole.
TEST(NeutralComponent, ADriftThatShrinksWithTheToleranceIsTheIntegratorsError) {
  const HeldComponent held{1, 3.0};
  ContinuationRequest request;
  request.from = 0.0;
  request.to = 0.4;
  request.start = {0.1};
  const double error = 100.0 * request.tolerance * 4.0;
  const ContinuationResult reduced =
      continue_branch(with_component_held(drifting_family(), held), request);
  ASSERT_EQ(reduced.stop_reason, StopReason::end_of_range) << reduced.stop_detail;

  ContinuationResult kept = reduced;
  end_where_held_component_drifts(kept, drifting_family(error), drifting_family(error / 100.0),
                                  held, request.tolerance);
  EXPECT_EQ(kept.stop_reason, StopReason::end_of_range);
  EXPECT_EQ(kept.branch.size(), reduced.branch.size());

  ContinuationResult ended = reduced;
  end_where_held_component_drifts(ended, drifting_family(error), drifting_family(error), held,
                                  request.tolerance);
  EXPECT_EQ(ended.stop_reason, StopReason::neutral_drift);
  EXPECT_TRUE(ended.branch.empty());
}

// The held component's image depends on the other one:
//     P(x; p) = (x0 / 2 + p, x1 + c (x0 − 2p)),  c = 1000,
// whose orbits (2p, any x1) do not drift. A point 1e-8 off in x0, within
// what the corrector accepts after a stalled step (residual 5e-9, under 100
// times the tolerance), drifts by 1e-5 on the map, seven times the bound;
// its residual says where the orbit is, and the drift left is the orbit's,
// none: the branch is kept.
TEST(NeutralComponent, TheDriftIsTheOrbitsNotThatOfAPointConvergedToTheTolerance) {
  constexpr double c = 1000.0;
  ContinuationProblem sensitive = drifting_family();
  sensitive.evaluate = [](const OrbitPoint& x, double p, double, bool, const ContactWindow&) {
    OrbitEvaluation e;
    e.completed = true;
    e.image = {0.5 * x[0] + p, x[1] + c * (x[0] - 2.0 * p)};
    e.monodromy = {{0.5, 0.0}, {c, 1.0}};
    e.span = 2.0 * M_PI;
    e.omega = 1.0;
    return e;
  };
  const HeldComponent held{1, 3.0};
  ContinuationResult branch;
  branch.stop_reason = StopReason::end_of_range;
  BranchPoint point;
  point.parameter = 0.2;
  point.state = {0.4 + 1e-8};
  branch.branch.push_back(point);
  const double tolerance = 1e-10;
  const double raw = sensitive.evaluate({point.state[0], held.value}, point.parameter, 0.0, false, {})
                         .image[1] - held.value;
  ASSERT_GT(std::fabs(raw), 5.0 * tolerance * (1.0 + 3.0 + c * (1.0 + 0.4)));
  end_where_held_component_drifts(branch, sensitive, sensitive, held, tolerance);
  EXPECT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  EXPECT_EQ(branch.branch.size(), 1u);
}

}  // namespace
}  // namespace impactlab
