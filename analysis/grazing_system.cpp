#include <impactlab/analysis/grazing_system.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/LU>

#include <impactlab/analysis/dense_solve.hpp>

namespace impactlab::detail {

template <int Size>
bool GrazingSystem<Size>::grazing_ahead(const std::vector<Node>& nodes, double h) {
  const Node& last = nodes.back();
  if (nodes.size() < 2) return false;
  const Node& before = nodes[nodes.size() - 2];
  auto vanishing = [&](double now, double earlier) {
    return std::isfinite(now) && earlier > now && now / (earlier - now) * last.step < h;
  };
  return vanishing(last.orbit.min_flight_gap, before.orbit.min_flight_gap) ||
         vanishing(last.orbit.min_impact_speed, before.orbit.min_impact_speed);
}

template <int Size>
std::optional<BifurcationPoint> GrazingSystem<Size>::grazing_within_reach(
    const std::vector<Node>& nodes, double h) {
  const Node& last = nodes.back();
  struct Candidate {
    int witness;
    double time;
    const char* kind;
  };
  std::vector<Candidate> candidates;
  // a candidate whose gap or speed, extrapolated linearly from the last two
  // points, vanishes within a few failed steps
  auto vanishing = [&](double OrbitEvaluation::*value) {
    const double now = last.orbit.*value;
    if (nodes.size() < 2) return true;
    const double before = nodes[nodes.size() - 2].orbit.*value;
    if (!(before > now)) return false;
    return now / (before - now) * last.step < 4.0 * h;
  };
  if (last.orbit.min_flight_gap_witness >= 0 && vanishing(&OrbitEvaluation::min_flight_gap))
    candidates.push_back({last.orbit.min_flight_gap_witness, last.orbit.min_flight_gap_time,
                          "a flight extremum touches the wall"});
  if (last.orbit.slowest_impact_witness >= 0 && vanishing(&OrbitEvaluation::min_impact_speed))
    candidates.push_back({last.orbit.slowest_impact_witness, last.orbit.slowest_impact_time,
                          "an impact velocity goes to zero"});
  // the candidate whose solution lies nearest along the branch first
  std::optional<BifurcationPoint> best;
  double best_s = INFINITY;
  for (const Candidate& candidate : candidates) {
    // the impact section's own wall: solved on the stroboscopic map
    const bool section_wall = candidate.witness == corrector_.problem().section_witness;
    auto solved = section_wall ? solve_section_wall(last)
                               : solve(last, candidate.witness, candidate.time, h);
    if (!solved) continue;
    const double s = last.tangent.dot(solved->y - last.y);
    if (s < -0.05 * h || s > 1.5 * h || s >= best_s) continue;
    solved->point.note = section_wall
                             ? "an impact velocity goes to zero: the section's own impact "
                               "(solved on the stroboscopic map)"
                             : candidate.kind;
    best = solved->point;
    best_s = s;
  }
  return best;
}

// Newton on z = (x, p, t_g) from the guess z, on the map `on` at section
// phase `phase`: Pⁿ(x; p) = x with the contacts of `witness` suppressed
// within nT/10 of the first guess of t_g, gap(t_g) = 0, gap rate(t_g) = 0;
// central-difference Jacobian. None where a run fails, Newton does not
// converge in 25 iterations, or t_g leaves the window.
template <int Size>
std::optional<typename GrazingSystem<Size>::Solution> GrazingSystem<Size>::newton(
    const ContinuationProblem& on, double phase, Extended z, int witness) {
  const int n = corrector_.dimension();
  const double scale = corrector_.scale();
  const double time = z[n + 1];
  const double span = corrector_.problem().forcing_period_at_p;
  const double half_width = span > 0.0 ? 0.1 * span : 0.1;
  const ContactWindow window{witness, time - half_width, time + half_width};
  auto residual_of = [&](const Extended& y, OrbitEvaluation* orbit) -> std::optional<Extended> {
    corrector_.count_evaluation();
    OrbitEvaluation e = on.evaluate(corrector_.state_of(y), y[n] * scale, phase, false, window);
    if (!e.completed) return std::nullopt;
    const GapSample gap =
        on.gap_at(corrector_.state_of(y), y[n] * scale, phase, window, y[n + 1]);
    if (!gap.completed) return std::nullopt;
    if (orbit) *orbit = e;
    Extended r(n + 2);
    for (int i = 0; i < n; ++i) r[i] = e.image[i] - y[i];
    r[n] = gap.value;
    r[n + 1] = gap.rate;
    return r;
  };
  const double tolerance = corrector_.request().tolerance;
  double last_parameter_step = INFINITY;
  for (int iteration = 0; iteration < 25; ++iteration) {
    OrbitEvaluation orbit;
    const auto r = residual_of(z, &orbit);
    if (!r) return std::nullopt;
    const double size = 1.0 + state_norm(z.data(), n);
    if (r->norm() <= tolerance * size && iteration > 0 &&
        std::fabs(last_parameter_step) <= 1e-11 * (1.0 + std::fabs(z[n])))
      return Solution{z, orbit, last_parameter_step, window};
    typename Spaces<Size>::ExtendedSquare jacobian(n + 2, n + 2);
    for (int j = 0; j < n + 2; ++j) {
      const double dz = 1e-7 * (1.0 + std::fabs(z[j]));
      Extended up = z, down = z;
      up[j] += dz;
      down[j] -= dz;
      const auto ru = residual_of(up, nullptr), rd = residual_of(down, nullptr);
      if (!ru || !rd) return std::nullopt;
      jacobian.col(j) = (*ru - *rd) / (2.0 * dz);
    }
    Extended step;
    if constexpr (Spaces<Size>::fixed)
      step = jacobian.fullPivLu().solve(-*r);
    else
      step = full_pivot_lu_solve(jacobian, -*r);
    if (!step.allFinite()) return std::nullopt;
    z += step;
    last_parameter_step = step[n];
    if (std::fabs(z[n + 1] - time) > half_width) return std::nullopt;  // left the window
  }
  return std::nullopt;
}

// The located point of a grazing solution: its parameter, multipliers and
// error estimate (Newton's last step in p, at least the tolerance).
template <int Size>
BifurcationPoint GrazingSystem<Size>::grazing_point(const Solution& solved, int witness) const {
  const double scale = corrector_.scale();
  BifurcationPoint point;
  point.type = BifurcationType::grazing;
  point.parameter = solved.z[corrector_.dimension()] * scale;
  point.multipliers = multipliers_of(solved.orbit.monodromy);
  const double tolerance = corrector_.request().tolerance;
  point.error_estimate = std::max(std::fabs(solved.parameter_step) * scale,
                                  tolerance * (1.0 + std::fabs(point.parameter)));
  point.graze_witness = witness;
  point.located = true;
  return point;
}

// The discontinuity map and normal form at a solution of the grazing system
// on the map `on` at section `phase` (none where the request skips them or
// the map gives no local flow).
template <int Size>
std::optional<GrazingNormalForm> GrazingSystem<Size>::normal_form_of(const ContinuationProblem& on,
                                                                     double phase,
                                                                     const Solution& solved,
                                                                     int witness) const {
  if (!corrector_.request().normal_forms || !on.grazing_flow) return std::nullopt;
  const int n = corrector_.dimension();
  ContactWindow window = solved.window;
  window.witness = witness;
  const double p = solved.z[n] * corrector_.scale();
  return grazing_normal_form(
      on.grazing_flow(corrector_.state_of(solved.z), p, phase, window, solved.z[n + 1]), p);
}

// The grazing system on the branch's own map, from the last point moved
// half the failed step along the branch, t_g from `time`.
template <int Size>
std::optional<typename GrazingSystem<Size>::Located> GrazingSystem<Size>::solve(
    const Node& last, int witness, double time, double h) {
  const int n = corrector_.dimension();
  Extended z(n + 2);
  z.head(n + 1) = last.y + 0.5 * h * last.tangent;
  z[n + 1] = time;
  const auto solved = newton(corrector_.problem(), corrector_.phase(), z, witness);
  if (!solved) return std::nullopt;
  BifurcationPoint point = grazing_point(*solved, witness);
  point.normal_form = normal_form_of(corrector_.problem(), corrector_.phase(), *solved, witness);
  point.state = corrector_.reported_state(solved->z.head(n + 1));
  point.graze_time = corrector_.time_since_requested_section(solved->z[n + 1], solved->orbit);
  return Located{point, solved->z.head(n + 1)};
}

// The impact section: the impact with the section's own wall grazes (the
// map ends there). The same grazing system, solved on the stroboscopic map
// problem.strobe at the phase half a forcing period after the last point's
// impact (so that the graze, one orbit after that impact, at t_g = nT − T/2,
// lies half a period from the section), from the last point carried there
// along the virtual orbit. Back on the impact section the point is
// (φ, q̇⁻) = (phase + ω (t_g − nT), q̇(t_g)): the graze is the section's own
// impact, touched at the section (graze_time 0).
template <int Size>
std::optional<typename GrazingSystem<Size>::Located> GrazingSystem<Size>::solve_section_wall(
    const Node& last) {
  const ContinuationProblem& problem = corrector_.problem();
  if (!problem.strobe || !problem.to_strobe || !(last.orbit.omega > 0.0)) return std::nullopt;
  const int n = corrector_.dimension();
  const ContinuationProblem& strobe = *problem.strobe;
  const double p = last.y[n] * corrector_.scale();
  const double phase = last.y[0] + std::numbers::pi;
  const auto carried = problem.to_strobe(corrector_.state_of(last.y), p, phase);
  if (!carried) return std::nullopt;
  Extended z(n + 2);
  for (int i = 0; i < n; ++i) z[i] = (*carried)[i];
  z[n] = last.y[n];
  z[n + 1] = last.orbit.span - std::numbers::pi / last.orbit.omega;
  const int witness = problem.section_witness;
  const auto solved = newton(strobe, phase, z, witness);
  if (!solved) return std::nullopt;
  const double t_g = solved->z[n + 1];
  const GapSample at = strobe.gap_at(corrector_.state_of(solved->z),
                                     solved->z[n] * corrector_.scale(), phase, solved->window, t_g);
  if (!at.completed || at.state.size() < 2) return std::nullopt;
  BifurcationPoint located = grazing_point(*solved, witness);
  located.normal_form = normal_form_of(strobe, phase, *solved, witness);
  located.state = {phase + solved->orbit.omega * (t_g - solved->orbit.span), at.state[1]};
  located.graze_time = 0.0;
  return Located{located, corrector_.point(located.state, solved->z[n])};
}

template class GrazingSystem<3>;
template class GrazingSystem<Eigen::Dynamic>;

}  // namespace impactlab::detail
