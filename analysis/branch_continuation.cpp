#include <impactlab/analysis/branch_continuation.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include <impactlab/analysis/bifurcation_location.hpp>
#include <impactlab/analysis/branch_corrector.hpp>
#include <impactlab/analysis/floquet_multipliers.hpp>
#include <impactlab/analysis/grazing_system.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

namespace {

using detail::BifurcationLocator;
using detail::BranchCorrector;
using detail::BranchNode;
using detail::GrazingSystem;
using detail::NodeCorrection;
using detail::Spaces;
using detail::StepControl;

// The branch driver: from a corrected start, predictor steps along the
// tangent, each corrected, accepted (its bifurcations located against the
// point before it) or halved, until the range ends or the branch does.
template <int Size>
class BranchDriver {
  using Vec = typename Spaces<Size>::Vec;
  using Node = BranchNode<Size>;
  using Correction = NodeCorrection<Size>;

 public:
  BranchDriver(const ContinuationProblem& problem, const ContinuationRequest& request)
      : problem_(problem),
        request_(request),
        corrector_(problem, request),
        steps_(request, corrector_.scale()),
        locator_(corrector_),
        grazing_(corrector_),
        n_(corrector_.dimension()),
        from_(request.from / corrector_.scale()),
        to_(request.to / corrector_.scale()) {}

  ContinuationResult run_from_start() {
    if (request_.start.size() != problem_.dimension)
      return stop(StopReason::start_not_converged,
                  "the start has " + std::to_string(request_.start.size()) +
                      " components, the orbit's state " + std::to_string(n_));
    const Vec start_point = corrector_.point(request_.start, from_);
    Correction start = corrector_.correct(start_point, corrector_.along_parameter(1.0),
                                          start_point, {}, nullptr);
    if (!start.converged)
      return stop(StopReason::start_not_converged,
                  "Newton at the start parameter did not converge");
    const double direction = request_.to >= request_.from ? 1.0 : -1.0;
    return run(start, corrector_.along_parameter(direction));
  }

  ContinuationResult run_from(const OrbitPoint& x, double p, const std::vector<double>& d) {
    if (x.size() != problem_.dimension || d.size() != problem_.dimension + 1)
      return stop(StopReason::start_not_converged,
                  "the switching point or direction does not match the orbit's state");
    Vec direction(n_ + 1);
    for (int i = 0; i <= n_; ++i) direction[i] = d[i];
    const Vec y0 = corrector_.point(x, p / corrector_.scale());
    const double offset =
        std::max(steps_.initial * 0.1, 1e-3 * (1.0 + detail::state_norm(x.data(), n_)));
    const Vec predicted = y0 + offset * direction.normalized();
    Correction start =
        corrector_.correct(predicted, direction.normalized(), predicted, {}, nullptr);
    if (!start.converged)
      return stop(StopReason::start_not_converged, "no orbit found off the switching point");
    return run(start, direction);
  }

 private:
  BranchPoint branch_point(const Node& node, double step) const {
    BranchPoint b;
    b.parameter = node.y[n_] * corrector_.scale();
    b.state = corrector_.reported_state(node.y);
    b.phase = problem_.phase;
    b.impacts = node.orbit.impacts;
    b.contact_phases = node.orbit.contact_phases;
    b.multipliers = multipliers_of(node.orbit);
    b.stable = std::all_of(b.multipliers.begin(), b.multipliers.end(),
                           [](const std::complex<double>& m) { return std::abs(m) < 1.0; });
    b.min_impact_speed = node.orbit.min_impact_speed;
    b.min_flight_gap = node.orbit.min_flight_gap;
    b.newton_iterations = node.iterations;
    b.step = step;
    return b;
  }

  bool accept(Correction& c, const Vec& along, double step) {
    const auto tangent = corrector_.tangent_at(c, along);
    if (!tangent) return false;
    Node node;
    node.y = c.y;
    node.tangent = *tangent;
    node.iterations = c.iterations;
    node.step = step;
    node.orbit = corrector_.evaluate(c.y, true, {});
    if (!node.orbit.completed) return false;
    if (!nodes_.empty()) locator_.detect(nodes_.back(), node, step, result_.points);
    move_section_off_events(node);
    nodes_.push_back(node);
    result_.branch.push_back(branch_point(node, step));
    return true;
  }

  // The fraction of the span between the section and the nearest event.
  static double clearance(const OrbitEvaluation& orbit, double shift_time) {
    double nearest = 0.5;
    for (double t : orbit.event_times) {
      double u = std::fmod(t - shift_time, orbit.span);
      if (u < 0.0) u += orbit.span;
      nearest = std::min({nearest, u / orbit.span, 1.0 - u / orbit.span});
    }
    return nearest;
  }

  // Where an event comes within 2 % of the span of the section (the
  // stroboscopic map jumps when an impact crosses it), the branch moves on to
  // the section phase, among 16, farthest from every event; the node is
  // carried there and corrected again. States are still reported on the
  // requested section.
  void move_section_off_events(Node& node) {
    if (!problem_.section_moves || node.orbit.span <= 0.0 || clearance(node.orbit, 0.0) > 0.02)
      return;
    const double phase = corrector_.phase();
    const double p = node.y[n_] * corrector_.scale();
    double best_phase = phase, best_clearance = clearance(node.orbit, 0.0);
    for (int j = 1; j < 16; ++j) {
      const double shift = 2.0 * std::numbers::pi * j / 16.0;
      const double value = clearance(node.orbit, shift / node.orbit.omega);
      if (value > best_clearance) {
        best_clearance = value;
        best_phase = std::remainder(phase + shift, 2.0 * std::numbers::pi);
      }
    }
    if (best_phase == phase) return;
    const auto moved = problem_.transport(corrector_.state_of(node.y), p, phase, best_phase);
    if (!moved) return;
    corrector_.move_section(best_phase);
    const Vec y = corrector_.point(*moved, node.y[n_]);
    Correction c = corrector_.correct(y, corrector_.along_parameter(1.0), y, {}, nullptr);
    const Vec along = corrector_.along_parameter(node.tangent[n_]);
    const auto tangent = c.converged ? corrector_.tangent_at(c, along) : std::nullopt;
    OrbitEvaluation orbit = c.converged ? corrector_.evaluate(c.y, true, {}) : OrbitEvaluation{};
    if (!tangent || !orbit.completed) {
      corrector_.move_section(phase);
      return;
    }
    node.y = c.y;
    node.tangent = *tangent;
    node.orbit = orbit;
  }

  // After a failed step h: a grazing point within reach ends the branch there.
  bool end_at_grazing(double h) {
    const auto point = grazing_.grazing_within_reach(nodes_, h);
    if (!point) return false;
    result_.points.push_back(*point);
    result_.stop_reason = StopReason::signature_change;
    result_.stop_detail = "grazing: " + point->note;
    return true;
  }

  ContinuationResult run(Correction& start, const Vec& along) {
    if (!accept(start, along, 0.0))
      return stop(StopReason::start_not_converged, "no branch tangent at the start");
    if (nodes_.back().orbit.one_sided) return stop_on_cone_edge();
    signature_ = nodes_.back().orbit.signature;
    double h = steps_.initial;
    const double direction = to_ >= from_ ? 1.0 : -1.0;
    while (static_cast<int>(nodes_.size()) < request_.max_points) {
      const Node& last = nodes_.back();
      const Vec tau = last.tangent;
      // the end of the range: land on p = to exactly
      const double remaining = (to_ - last.y[n_]) * direction;
      if (remaining <= 1e-12 * (1.0 + std::fabs(to_))) return finish();
      if ((last.y[n_] - from_) * direction < -1e-3 * std::fabs(to_ - from_))
        return stop(StopReason::left_range, "the branch turned back past the start of the range");
      const double toward_end = tau[n_] * direction;
      if (toward_end > 0.0 && h * toward_end >= remaining) {
        const double h_end = remaining / toward_end;
        Vec predicted = last.y + h_end * tau;
        predicted[n_] = to_;
        Correction c = corrector_.correct(predicted, corrector_.along_parameter(1.0), predicted,
                                          {}, &signature_);
        if (c.converged && accept(c, tau, h_end))
          return nodes_.back().orbit.one_sided ? stop_on_cone_edge() : finish();
        if (c.signature_changed && end_at_grazing(h_end)) return finish();
        h = 0.5 * std::min(h, h_end);
        if (h < steps_.smallest)
          return stop(StopReason::branch_point, "the corrector fails before the end of the range");
        continue;
      }
      const Vec predicted = last.y + h * tau;
      Correction c = corrector_.correct(predicted, tau, predicted, {}, &signature_);
      bool ok = c.converged;
      if (ok) {
        const auto turned = corrector_.tangent_at(c, tau);
        ok = turned && turned->dot(tau) > std::cos(30.0 * std::numbers::pi / 180.0);
      }
      if (ok && accept(c, tau, h)) {
        if (nodes_.back().orbit.one_sided) return stop_on_cone_edge();
        // a gap or impact speed about to vanish: end at the grazing point
        // before Newton meets the square-root singularity
        if (GrazingSystem<Size>::grazing_ahead(nodes_, h) && end_at_grazing(h)) return finish();
        // a corrector that only creeps (steps below 1e-5 of the range for
        // 100 points: an orbit so unstable that the integrator's noise in Pⁿ
        // exceeds the tolerance): a grazing point within reach, or a stop
        stalled_ = h < 1e-5 ? stalled_ + 1 : 0;
        if (stalled_ >= 100) {
          if (end_at_grazing(steps_.largest)) return finish();
          return stop(StopReason::branch_point,
                      "stalled: steps below 1e-5 of the range for 100 points");
        }
        h = steps_.after_success(h, c.iterations);
        continue;
      }
      if ((c.signature_changed || !c.converged) && end_at_grazing(h)) return finish();
      h *= 0.5;
      if (h < steps_.smallest && c.signature_changed)
        return stop(StopReason::signature_change,
                    "the impact signature changes from '" + signature_ + "' to '" +
                        c.orbit.signature + "'; no grazing point located");
      if (h < steps_.smallest)
        return stop(StopReason::branch_point,
                    "step below the smallest: the corrector cannot pass this point");
    }
    return stop(StopReason::max_points, "the branch reached the point limit");
  }

  // The last point's orbit has an impulse on the friction cone's edge: its
  // multipliers do not exist, nor does a tangent to follow the branch by.
  ContinuationResult stop_on_cone_edge() {
    return stop(StopReason::no_tangent_map,
                "the orbit at " + to_text(result_.branch.back().parameter) +
                    " has an impulse on the friction cone's edge: no multipliers");
  }

  ContinuationResult stop(StopReason reason, const std::string& detail) {
    result_.stop_reason = reason;
    result_.stop_detail = detail;
    return finish();
  }

  ContinuationResult finish() {
    result_.map_evaluations = corrector_.map_evaluations();
    return std::move(result_);
  }

  const ContinuationProblem& problem_;
  const ContinuationRequest& request_;
  BranchCorrector<Size> corrector_;
  StepControl steps_;
  BifurcationLocator<Size> locator_;
  GrazingSystem<Size> grazing_;
  int n_ = 2;                     // N: the state's components on the section
  double from_ = 0.0, to_ = 1.0;  // the range in branch units
  int stalled_ = 0;               // consecutive points reached by tiny steps
  std::vector<Node> nodes_;
  std::string signature_;
  ContinuationResult result_;
};

}  // namespace

ContinuationResult continue_branch(const ContinuationProblem& problem,
                                   const ContinuationRequest& request) {
  if (problem.dimension == 2) return BranchDriver<3>(problem, request).run_from_start();
  return BranchDriver<Eigen::Dynamic>(problem, request).run_from_start();
}

ContinuationResult continue_branch_from(const ContinuationProblem& problem,
                                        const ContinuationRequest& request,
                                        const OrbitPoint& x, double p,
                                        const std::vector<double>& direction) {
  if (problem.dimension == 2) return BranchDriver<3>(problem, request).run_from(x, p, direction);
  return BranchDriver<Eigen::Dynamic>(problem, request).run_from(x, p, direction);
}

}  // namespace impactlab
