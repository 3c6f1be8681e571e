#include <impactlab/analysis/bifurcation_location.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/LU>
#include <boost/math/tools/roots.hpp>

#include <impactlab/analysis/chatter_onset.hpp>

namespace impactlab {

namespace {

// det(M ± I) for N > 2, by a fully pivoted LU decomposition of M with
// `shift` (std::minus or std::plus) applied to I entry by entry
template <class Shift>
double determinant_shifted(const MonodromyMatrix& m, Shift shift) {
  const auto n = static_cast<Eigen::Index>(m.size());
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = shift(m[i][j], i == j ? 1.0 : 0.0);
  return a.fullPivLu().determinant();
}

bool all_real(const std::vector<std::complex<double>>& multipliers) {
  return std::all_of(multipliers.begin(), multipliers.end(),
                     [](const std::complex<double>& z) { return z.imag() == 0.0; });
}

std::string count_change_note(int OrbitEvaluation::*count, int before, int after) {
  const std::string what =
      count == &OrbitEvaluation::contact_phases ? "contact phases" : "stick impacts";
  return what + " per orbit " + std::to_string(before) + " -> " + std::to_string(after);
}

}  // namespace

double det_minus_identity(const MonodromyMatrix& m) {
  if (m.size() == 2) return (m[0][0] - 1.0) * (m[1][1] - 1.0) - m[0][1] * m[1][0];
  return determinant_shifted(m, std::minus<>());
}

double det_plus_identity(const MonodromyMatrix& m) {
  if (m.size() == 2) return (m[0][0] + 1.0) * (m[1][1] + 1.0) - m[0][1] * m[1][0];
  return determinant_shifted(m, std::plus<>());
}

double neimark_sacker_test(const MonodromyMatrix& m) {
  if (m.size() == 2) return m[0][0] * m[1][1] - m[0][1] * m[1][0] - 1.0;
  const auto lambda = multipliers_of(m);
  std::complex<double> product = 1.0;
  for (std::size_t i = 0; i < lambda.size(); ++i)
    for (std::size_t j = i + 1; j < lambda.size(); ++j) product *= lambda[i] * lambda[j] - 1.0;
  return product.real();
}

namespace detail {

template <int Size>
void BifurcationLocator<Size>::detect(const Node& a, const Node& b, double step,
                                      std::vector<BifurcationPoint>& points) {
  struct Test {
    BifurcationType type;
    double (*function)(const MonodromyMatrix&);
  };
  static constexpr Test tests[] = {{BifurcationType::fold, &det_minus_identity},
                                   {BifurcationType::period_doubling, &det_plus_identity},
                                   {BifurcationType::neimark_sacker, &neimark_sacker_test}};
  const int n = corrector_.dimension();
  for (const Test& test : tests) {
    const double fa = test.function(a.orbit.monodromy), fb = test.function(b.orbit.monodromy);
    if (!(fa * fb < 0.0)) continue;
    // a complex pair on the unit circle, not a real pair with product 1
    if (test.type == BifurcationType::neimark_sacker &&
        all_real(multipliers_of(a.orbit.monodromy)) && all_real(multipliers_of(b.orbit.monodromy)))
      continue;
    BifurcationPoint point = locate(test.type, test.function, a, step, fa, fb);
    // a multiplier through +1 where the branch does not turn back in p: a
    // branch point (a symmetry-breaking pitchfork or a transcritical point)
    if (point.type == BifurcationType::fold && a.tangent[n] * b.tangent[n] > 0.0)
      point.type = BifurcationType::branch_point;
    points.push_back(point);
  }
  // a scene's boundaries say where impacts or contact phases become possible:
  // none concerns an orbit that meets no wall on either side (the hanging
  // pendulum)
  if (a.orbit.impacts > 0 || b.orbit.impacts > 0)
    for (const ParameterBoundary& boundary : corrector_.problem().boundaries)
      if (auto point = locate_boundary(boundary, a, b)) points.push_back(*point);
  detect_count_changes(a, b, step, points);
}

template <int Size>
void BifurcationLocator<Size>::detect_count_changes(const Node& a, const Node& b, double step,
                                                    std::vector<BifurcationPoint>& points) {
  for (int OrbitEvaluation::*count : {&OrbitEvaluation::contact_phases, &OrbitEvaluation::stick_impacts})
    if (a.orbit.*count != b.orbit.*count) points.push_back(locate_count_change(count, a, b, step));
}

// A count per orbit (contact phases, or impacts that stick) differs between
// nodes a and b (reached by the step `step` from a): bisection on the arclength s from a, each trial
// point corrected onto the branch (the hyperplane through a + s τ normal to
// τ, as the step itself), the side decided by the trial orbit's count, down
// to a bracket of 1e-10 of the range in p (or 1e-13 in s where the branch
// is nearly normal to p). The point is the corrected orbit at the middle of
// the last bracket; its error estimate is the bracket in p. A contact
// phase's onset or end is located instead at the root of the landing push
// (TOMS 748 on the arclength, each trial point corrected onto the branch)
// where both nodes land with pushes of opposite signs.
template <int Size>
BifurcationPoint BifurcationLocator<Size>::locate_count_change(int OrbitEvaluation::*count,
                                                               const Node& a, const Node& b,
                                                               double step) {
  const int n = corrector_.dimension();
  const double scale = corrector_.scale();
  BifurcationPoint point;
  const bool grows = b.orbit.*count > a.orbit.*count;
  if (count == &OrbitEvaluation::contact_phases)
    point.type = grows ? BifurcationType::contact_onset : BifurcationType::contact_end;
  else
    point.type = grows ? BifurcationType::stick_onset : BifurcationType::stick_end;
  point.parameter = 0.5 * (a.y[n] + b.y[n]) * scale;
  point.state = corrector_.reported_state(b.y);
  point.multipliers = multipliers_of(b.orbit);
  point.error_estimate = 0.5 * std::fabs(b.y[n] - a.y[n]) * scale;
  point.note = "detected between two branch points";
  if (!corrector_.request().locate) return point;
  // a contact phase that a chatter lands in: it appears or ends where the
  // chatter starts or stops completing (the landing push is not smooth there)
  if (count == &OrbitEvaluation::contact_phases &&
      (a.orbit.chatter_side != 0 || b.orbit.chatter_side != 0))
    if (auto onset = chatter_onset_from(a.y, b.y,
                                        count_change_note(count, a.orbit.*count, b.orbit.*count)))
      return *onset;
  const Vec& tau = a.tangent;
  auto corrected_at = [&](double s) {
    const Vec predicted = a.y + s * tau;
    return corrector_.correct(predicted, tau, predicted, {}, nullptr);
  };
  // a contact phase's onset or end where both ends land on the wall with
  // pushes of opposite signs: the root of the landing push, the contact
  // boundary's own defining condition (contact_landing.hpp)
  const double push_a = a.orbit.landing_push, push_b = b.orbit.landing_push;
  if (count == &OrbitEvaluation::contact_phases && push_a * push_b < 0.0) {
    std::optional<Correction> last;
    auto push_on_branch = [&](double s) -> double {
      Correction c = corrected_at(s);
      if (!c.converged || !std::isfinite(c.orbit.landing_push))
        throw std::runtime_error("corrector failed");
      const double value = c.orbit.landing_push;
      last = std::move(c);
      return value;
    };
    try {
      std::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(
          push_on_branch, 0.0, step, push_a, push_b, boost::math::tools::eps_tolerance<double>(42),
          iterations);
      push_on_branch(0.5 * (bracket.first + bracket.second));
      point.parameter = last->y[n] * scale;
      point.state = corrector_.reported_state(last->y);
      point.multipliers = multipliers_of(last->orbit);
      // the bracket, and the corrector's tolerance: the orbit is converged
      // only to it, and its landing time with it
      point.error_estimate = std::fabs(tau[n]) * (bracket.second - bracket.first) * scale +
                             corrector_.request().tolerance * (1.0 + std::fabs(point.parameter));
      point.located = true;
      point.note = count_change_note(count, a.orbit.*count, b.orbit.*count) +
                   ", at the root of the push on the mass at rest at its landing";
      return point;
    } catch (const std::exception&) {
      // the bisection on the count below
    }
  }
  double low = 0.0, high = step;         // a's count at low, another at high
  double p_low = a.y[n], p_high = b.y[n];  // the corrected ends' p (range units)
  bool failed = false;
  for (int bisection = 0; bisection < 80; ++bisection) {
    if (std::fabs(p_high - p_low) <= 1e-10 || high - low <= 1e-13) break;
    const double middle = 0.5 * (low + high);
    const Correction c = corrected_at(middle);
    if (!c.converged) {
      failed = true;
      break;
    }
    if (c.orbit.*count == a.orbit.*count) {
      low = middle;
      p_low = c.y[n];
    } else {
      high = middle;
      p_high = c.y[n];
    }
  }
  const Correction c = failed ? Correction{} : corrected_at(0.5 * (low + high));
  if (c.converged) {
    point.parameter = c.y[n] * scale;
    point.state = corrector_.reported_state(c.y);
    point.multipliers = multipliers_of(c.orbit);
    point.error_estimate = std::fabs(p_high - p_low) * scale;
    point.located = true;
    point.note = count_change_note(count, a.orbit.*count, b.orbit.*count);
  } else {
    point.note = "detected; the corrector failed while locating it";
  }
  return point;
}

// The onset of complete chatter near the points y0 and y1 of the branch
// (solve_chatter_onset, chatter_onset.hpp), with `what` leading its note.
template <int Size>
std::optional<BifurcationPoint> BifurcationLocator<Size>::chatter_onset_from(
    const Vec& y0, const Vec& y1, const std::string& what) {
  const int n = corrector_.dimension();
  const double scale = corrector_.scale();
  const OrbitAt orbit_at = [&](const OrbitPoint& x, double p) {
    return corrector_.evaluate(corrector_.point(x, p / scale), false, {});
  };
  const ChatterOnset onset = solve_chatter_onset(orbit_at, corrector_.state_of(y0), y0[n] * scale,
                                                 corrector_.state_of(y1), y1[n] * scale);
  if (!onset.found) return std::nullopt;
  BifurcationPoint point;
  point.type = BifurcationType::chatter_onset;
  point.parameter = onset.parameter;
  point.state = corrector_.reported_state(corrector_.point(onset.state, onset.parameter / scale));
  point.multipliers = multipliers_of(onset.orbit);
  point.error_estimate = onset.error_estimate;
  point.located = true;
  point.note = what + ": its impacts follow the self-similar chatter that accumulates where "
                      "the push vanishes";
  return point;
}

// A parameter boundary crossed between nodes a and b: its root in p (TOMS
// 748 on the boundary's own function), and the orbit corrected there at
// fixed p from the point of the secant a–b at that p. None where it is not
// crossed.
template <int Size>
std::optional<BifurcationPoint> BifurcationLocator<Size>::locate_boundary(
    const ParameterBoundary& boundary, const Node& a, const Node& b) {
  const int n = corrector_.dimension();
  const double scale = corrector_.scale();
  const double pa = a.y[n] * scale, pb = b.y[n] * scale;
  const double fa = boundary.value(pa), fb = boundary.value(pb);
  if (!(fa * fb < 0.0)) return std::nullopt;
  BifurcationPoint point;
  point.type = BifurcationType::boundary;
  point.boundary = boundary.name;
  point.note = boundary.note;
  std::uintmax_t iterations = 100;
  const auto bracket = boost::math::tools::toms748_solve(
      [&](double p) { return boundary.value(p); }, std::min(pa, pb), std::max(pa, pb),
      pa < pb ? fa : fb, pa < pb ? fb : fa, boost::math::tools::eps_tolerance<double>(52),
      iterations);
  point.parameter = 0.5 * (bracket.first + bracket.second);
  point.error_estimate = bracket.second - bracket.first;
  const double fraction = (point.parameter - pa) / (pb - pa);
  Vec guess = a.y + fraction * (b.y - a.y);
  guess[n] = point.parameter / scale;
  Correction c = corrector_.correct(guess, corrector_.along_parameter(1.0), guess, {}, nullptr);
  if (c.converged) {
    point.state = corrector_.reported_state(c.y);
    point.multipliers = multipliers_of(c.orbit.monodromy);
    point.located = true;
  } else {
    point.state = corrector_.reported_state(guess);
    point.note += " (the orbit there interpolated: the corrector failed)";
  }
  return point;
}

// The root of a test function on the arclength from node a, each trial
// point corrected onto the branch (TOMS 748).
template <int Size>
BifurcationPoint BifurcationLocator<Size>::locate(BifurcationType type,
                                                  double (*function)(const MonodromyMatrix&),
                                                  const Node& a, double step, double fa,
                                                  double fb) {
  const int n = corrector_.dimension();
  const double scale = corrector_.scale();
  BifurcationPoint point;
  point.type = type;
  std::optional<Correction> last;
  auto on_branch = [&](double s) -> double {
    const Vec predicted = a.y + s * a.tangent;
    Correction c = corrector_.correct(predicted, a.tangent, predicted, {}, nullptr);
    if (!c.converged) throw std::runtime_error("corrector failed");
    const double value = function(c.orbit.monodromy);
    last = std::move(c);
    return value;
  };
  if (!corrector_.request().locate) {
    point.note = "detected (location off)";
    point.error_estimate = std::fabs(step * a.tangent[n]) * scale;
    point.parameter = (a.y[n] + 0.5 * step * a.tangent[n]) * scale;
    return point;
  }
  try {
    std::uintmax_t iterations = 100;
    const auto bracket = boost::math::tools::toms748_solve(
        on_branch, 0.0, step, fa, fb, boost::math::tools::eps_tolerance<double>(42), iterations);
    const double s = 0.5 * (bracket.first + bracket.second);
    on_branch(s);
    point.parameter = last->y[n] * scale;
    point.state = corrector_.reported_state(last->y);
    point.multipliers = multipliers_of(last->orbit.monodromy);
    point.error_estimate = std::fabs(a.tangent[n]) * (bracket.second - bracket.first) * scale;
    point.located = true;
  } catch (const std::exception&) {
    point.parameter = (a.y[n] + 0.5 * step * a.tangent[n]) * scale;
    point.error_estimate = std::fabs(step * a.tangent[n]) * scale;
    point.note = "detected; the corrector failed while locating it";
  }
  return point;
}

template class BifurcationLocator<3>;
template class BifurcationLocator<Eigen::Dynamic>;

}  // namespace detail

}  // namespace impactlab
