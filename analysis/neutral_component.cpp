// Holding a neutral component of a continuation's section state (neutral_component.hpp).
#include <impactlab/analysis/neutral_component.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <Eigen/Core>

#include <impactlab/analysis/dense_solve.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

std::optional<std::size_t> neutral_component(const MonodromyMatrix& monodromy, double tolerance) {
  const std::size_t n = monodromy.size();
  for (std::size_t column = 0; column < n; ++column) {
    bool neutral = true;
    for (std::size_t row = 0; row < n && neutral; ++row) {
      const double unit = row == column ? 1.0 : 0.0;
      neutral = std::fabs(monodromy[row][column] - unit) <= tolerance;
    }
    if (neutral) return column;
  }
  return std::nullopt;
}

OrbitPoint with_held_component(const OrbitPoint& reduced, const HeldComponent& held) {
  OrbitPoint full = reduced;
  if (full.empty()) return full;
  full.insert(full.begin() + static_cast<std::ptrdiff_t>(held.index), held.value);
  return full;
}

OrbitPoint without_held_component(const OrbitPoint& full, const HeldComponent& held) {
  OrbitPoint reduced = full;
  if (reduced.size() > held.index)
    reduced.erase(reduced.begin() + static_cast<std::ptrdiff_t>(held.index));
  return reduced;
}

std::vector<std::complex<double>> with_neutral_multiplier(
    std::vector<std::complex<double>> multipliers) {
  if (multipliers.empty()) return multipliers;
  multipliers.emplace_back(1.0, 0.0);
  std::stable_sort(multipliers.begin(), multipliers.end(),
                   [](const std::complex<double>& a, const std::complex<double>& b) {
                     return std::abs(a) > std::abs(b);
                   });
  return multipliers;
}

namespace {

// The drift of the orbit itself, from the map evaluated at a point whose
// other components o are converged only to the corrector's tolerance: their
// residual r_o = P_o(x) − x_o puts them (M_oo − I)⁻¹ r_o off the orbit, which
// moves the held component's image by M_co times that. So the orbit's drift
// is d − M_co (M_oo − I)⁻¹ r_o (one Newton step's worth); d where M_oo − I
// is singular.
double orbit_drift(const OrbitEvaluation& at, const OrbitPoint& x, std::size_t held) {
  const double drift = at.image[held] - x[held];
  const std::size_t n = x.size();
  if (n < 2 || at.monodromy.size() != n) return drift;
  const auto other = [held](std::size_t k) { return k < held ? k : k + 1; };
  const Eigen::Index m = static_cast<Eigen::Index>(n - 1);
  Eigen::MatrixXd shifted(m, m);
  Eigen::VectorXd residual(m), row(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    const std::size_t oi = other(static_cast<std::size_t>(i));
    residual[i] = at.image[oi] - x[oi];
    row[i] = at.monodromy[held][oi];
    for (Eigen::Index j = 0; j < m; ++j)
      shifted(i, j) = at.monodromy[oi][other(static_cast<std::size_t>(j))] - (i == j ? 1.0 : 0.0);
  }
  const Eigen::VectorXd offset = full_pivot_lu_solve(shifted, residual);
  if (!offset.allFinite()) return drift;
  return drift - row.dot(offset);
}

}  // namespace

void end_where_held_component_drifts(ContinuationResult& branch, const ContinuationProblem& full,
                                     const ContinuationProblem& tighter, const HeldComponent& held,
                                     double tolerance) {
  for (std::size_t k = 0; k < branch.branch.size(); ++k) {
    const BranchPoint& point = branch.branch[k];
    const OrbitPoint x = with_held_component(point.state, held);
    const OrbitEvaluation at = full.evaluate(x, point.parameter, point.phase, false, {});
    if (!at.completed) continue;
    const double drift = orbit_drift(at, x, held.index);
    // what is left of the other components' error after the correction
    // moves the drift by the monodromy's row
    double size = 0.0, sensitivity = 0.0;
    for (double component : point.state) size = std::max(size, std::fabs(component));
    for (std::size_t j = 0; j < at.monodromy.size(); ++j)
      if (j != held.index) sensitivity += std::fabs(at.monodromy[held.index][j]);
    const double allowed =
        tolerance * (1.0 + std::fabs(held.value) + sensitivity * (1.0 + size));
    if (std::fabs(drift) <= allowed) continue;
    const OrbitEvaluation tight = tighter.evaluate(x, point.parameter, point.phase, false, {});
    if (tight.completed && std::fabs(orbit_drift(tight, x, held.index)) < 0.5 * std::fabs(drift))
      continue;
    const double where = point.parameter;
    branch.branch.resize(k);
    // the located points within the parameters the kept points span
    double low = where, high = where;
    for (const BranchPoint& kept : branch.branch) {
      low = std::min(low, kept.parameter);
      high = std::max(high, kept.parameter);
    }
    std::erase_if(branch.points, [&](const BifurcationPoint& located) {
      return branch.branch.empty() || located.parameter < low || located.parameter > high ||
             located.parameter == where;
    });
    branch.stop_reason = StopReason::neutral_drift;
    branch.stop_detail = "state component " + std::to_string(held.index + 1) + " changes by " +
                         to_text(drift) + " over the orbit at " + to_text(where) +
                         ": the motion is periodic in the other components only";
    return;
  }
}

void restore_held_component(ContinuationJobResult& result, const HeldComponent& held) {
  const auto restore = [&held](auto& point) {
    point.state = with_held_component(point.state, held);
    point.multipliers = with_neutral_multiplier(std::move(point.multipliers));
  };
  for (ContinuedBranch& branch : result.branches) {
    for (BranchPoint& point : branch.result.branch) restore(point);
    for (BifurcationPoint& point : branch.result.points) restore(point);
  }
  for (CurvePoint& point : result.curve.curve) restore(point);
  for (BranchCurve& doubled : result.doubled_curves)
    for (CurvePoint& point : doubled.curve.curve) restore(point);
}

namespace {

MonodromyMatrix without_row_and_column(const MonodromyMatrix& full, std::size_t index) {
  MonodromyMatrix reduced;
  for (std::size_t row = 0; row < full.size(); ++row) {
    if (row == index) continue;
    std::vector<double> entries;
    for (std::size_t column = 0; column < full[row].size(); ++column)
      if (column != index) entries.push_back(full[row][column]);
    reduced.push_back(std::move(entries));
  }
  return reduced;
}

}  // namespace

ContinuationProblem with_component_held(const ContinuationProblem& full, const HeldComponent& held) {
  auto base = std::make_shared<const ContinuationProblem>(full);
  ContinuationProblem problem = full;
  problem.dimension = full.dimension - 1;
  problem.evaluate = [base, held](const OrbitPoint& x, double p, double phase, bool detailed,
                                  const ContactWindow& suppressed) {
    OrbitEvaluation at = base->evaluate(with_held_component(x, held), p, phase, detailed, suppressed);
    if (!at.completed) return at;
    at.image = without_held_component(at.image, held);
    at.monodromy = without_row_and_column(at.monodromy, held.index);
    return at;
  };
  problem.gap_at = [base, held](const OrbitPoint& x, double p, double phase,
                                const ContactWindow& suppressed, double t) {
    GapSample sample = base->gap_at(with_held_component(x, held), p, phase, suppressed, t);
    if (sample.completed) sample.state = without_held_component(sample.state, held);
    return sample;
  };
  problem.transport = [base, held](const OrbitPoint& x, double p, double from,
                                   double to) -> std::optional<OrbitPoint> {
    const auto moved = base->transport(with_held_component(x, held), p, from, to);
    if (!moved) return std::nullopt;
    return without_held_component(*moved, held);
  };
  if (full.strobe)
    problem.strobe =
        std::make_shared<const ContinuationProblem>(with_component_held(*full.strobe, held));
  if (full.to_strobe)
    problem.to_strobe = [base, held](const OrbitPoint& x, double p,
                                     double phase) -> std::optional<OrbitPoint> {
      const auto moved = base->to_strobe(with_held_component(x, held), p, phase);
      if (!moved) return std::nullopt;
      return without_held_component(*moved, held);
    };
  return problem;
}

}  // namespace impactlab
