#include <impactlab/analysis/branch_continuation.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <memory>
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
    // a forced stick's monodromy is not the real map's, which has none
    b.multipliers = forced_map_ && entered_cone_edge_
                        ? missing_multipliers(node.orbit.monodromy.size())
                        : multipliers_of(node.orbit);
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
    // on the forced stick's map the monodromy is not the real map's: only
    // the contact phases are watched there (a change of the stick impacts
    // is a corner, cross_corner)
    if (!nodes_.empty() && !forced_map_) locator_.detect(nodes_.back(), node, step, result_.points);
    if (!nodes_.empty() && forced_map_) note_contact_changes(node, step);
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
      // where an impact starts or stops sticking and an impulse can sit on
      // the friction cone's edge, the branch turns at a corner, past which
      // the step has landed: on the forced stick's map the corner is
      // crossed there (cross_corner); on the real map, where an impact
      // stops sticking, the forced map's branch takes over from the last
      // point (follow_cone_edge)
      if (ok && c.orbit.stick_impacts != nodes_.back().orbit.stick_impacts) {
        if (forced_map_) {
          if (cross_corner(direction, &c, std::fabs(h * tau[n_]))) {
            if (left_cone_edge_) return finish();
            continue;
          }
          ok = false;
        } else if (c.orbit.stick_impacts < nodes_.back().orbit.stick_impacts) {
          // where no edge runs on from there, the step is taken as it is
          if (auto along_edge = follow_cone_edge(nodes_.back().orbit.stuck_witness, false))
            return std::move(*along_edge);
        }
      }
      if (ok) {
        const auto turned = corrector_.tangent_at(c, tau);
        ok = turned && turned->dot(tau) > std::cos(30.0 * std::numbers::pi / 180.0);
      }
      if (ok && accept(c, tau, h)) {
        if (left_cone_edge_) return finish();
        // the forced map's branch is wanted only through a corner onto the
        // edge, which lies within the first steps from an interior point
        if (forced_map_ && !entered_cone_edge_ && nodes_.size() > 4)
          return stop(StopReason::branch_point, "no corner onto the friction cone's edge");
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
      if (h < steps_.smallest) {
        // the corner of an impulse reaching the friction cone's edge
        if (forced_map_ && cross_corner(direction, nullptr, 0.0)) {
          if (left_cone_edge_) return finish();
          h = steps_.initial;
          continue;
        }
        if (auto along_edge = follow_cone_edge(nodes_.back().orbit.stuck_witness, false))
          return std::move(*along_edge);
        return stop(StopReason::branch_point,
                    "step below the smallest: the corrector cannot pass this point");
      }
    }
    return stop(StopReason::max_points, "the branch reached the point limit");
  }

  // On the forced stick's map: changes of the contact phases, located there;
  // their multipliers are the real map's, which do not exist on the edge.
  void note_contact_changes(const Node& node, double step) {
    const std::size_t before = result_.points.size();
    if (node.orbit.contact_phases != nodes_.back().orbit.contact_phases)
      locator_.detect_count_changes(nodes_.back(), node, step, result_.points);
    for (std::size_t i = before; i < result_.points.size(); ++i)
      result_.points[i].multipliers = missing_multipliers(node.orbit.monodromy.size());
  }

  // On the forced stick's map, where the stick impacts per orbit change,
  // the branch turns at a corner. A point past it is accepted: `landed`, a
  // step's corrected point there, where it lies within twice the step's
  // `reach` in p (past a corner the branch can run almost normal to the
  // step, and the corrector far along it); or else one from the last point
  // at fixed p, `reach` on, then 4, 40 and 400 smallest steps on. Fewer
  // stick impacts: another impact starts to slide, and the
  // forced impulse goes onto the cone's edge (`stick_end`; from here on no
  // multipliers). More: another impact starts to stick, the forced impulse
  // leaves the edge (`stick_onset`), and the real map takes over. The
  // corner is located on the real map, from the side where every impact
  // sticks inside the cone (its smooth side): by bisection in p, each trial
  // corrected at fixed p from that side's orbit, the side decided by the
  // trial converging with that side's stick impacts, to 1e-13 relative. A
  // step at fixed p that meets no corner is accepted as a plain point.
  // False where none converges.
  bool cross_corner(double direction, const Correction* landed, double reach) {
    const Node a = nodes_.back();
    auto fixed_parameter = [](BranchCorrector<Size>& corrector, double p, const Vec& from,
                              const std::string* signature) {
      Vec y = from;
      y[y.size() - 1] = p;
      return corrector.correct(y, corrector.along_parameter(1.0), y, {}, signature);
    };
    std::vector<double> steps;  // fixed-p steps from a, after `landed`
    if (reach > 0.0) steps.push_back(reach);
    for (double multiple : {4.0, 40.0, 400.0}) steps.push_back(multiple * steps_.smallest);
    const bool landed_near =
        landed != nullptr && std::fabs(landed->y[n_] - a.y[n_]) <= 2.0 * reach;
    for (std::size_t attempt = landed_near ? 0 : 1; attempt <= steps.size(); ++attempt) {
      Correction past = attempt == 0 ? *landed
                                     : fixed_parameter(corrector_,
                                                       a.y[n_] + steps[attempt - 1] * direction,
                                                       a.y, &signature_);
      if (!past.converged) continue;
      const double dp = past.y[n_] - a.y[n_];
      const int sticks = past.orbit.stick_impacts;
      if (sticks == a.orbit.stick_impacts)
        return accept(past, corrector_.along_parameter(direction), std::fabs(dp));
      const bool onto_edge = sticks < a.orbit.stick_impacts;
      // the side where every impact sticks inside the cone, on the real map
      BranchCorrector<Size> real(*real_problem_, request_);
      Vec inside_y = onto_edge ? a.y : past.y;
      const int inside_sticks = std::max(sticks, a.orbit.stick_impacts);
      double inside = inside_y[n_], outside = onto_edge ? past.y[n_] : a.y[n_];
      for (int bisection = 0; bisection < 60; ++bisection) {
        if (std::fabs(outside - inside) <= 1e-13 * (1.0 + std::fabs(inside))) break;
        const double middle = 0.5 * (inside + outside);
        const Correction trial = fixed_parameter(real, middle, inside_y, nullptr);
        if (trial.converged && trial.orbit.stick_impacts == inside_sticks) {
          inside = middle;
          inside_y = trial.y;
        } else {
          outside = middle;
        }
      }
      BifurcationPoint point;
      point.type = onto_edge ? BifurcationType::stick_end : BifurcationType::stick_onset;
      point.parameter = inside * corrector_.scale();
      point.state = corrector_.reported_state(inside_y);
      point.multipliers = missing_multipliers(a.orbit.monodromy.size());
      point.error_estimate = std::fabs(outside - inside) * corrector_.scale() +
                             request_.tolerance * (1.0 + std::fabs(point.parameter));
      point.located = true;
      point.note = "stick impacts per orbit " + std::to_string(a.orbit.stick_impacts) + " -> " +
                   std::to_string(sticks) +
                   (onto_edge ? ": an impact starts to slide, the other's impulse goes onto "
                                "the friction cone's edge"
                              : ": an impact starts to stick, the impulse on the friction "
                                "cone's edge leaves it") +
                   " (a corner of the branch, located at fixed parameter)";
      real_map_evaluations_ += real.map_evaluations();
      bool& crossed = onto_edge ? entered_cone_edge_ : left_cone_edge_;
      crossed = true;  // before accept: the point past the corner is on its side
      if (!accept(past, corrector_.along_parameter(direction), std::fabs(dp))) {
        crossed = false;
        return false;
      }
      result_.points.push_back(point);
      return true;
    }
    return false;
  }

  // The last point's orbit has an impulse on the friction cone's edge: its
  // multipliers do not exist, nor does a tangent to follow the branch by.
  // Where the problem can force that impact to stick, the branch goes on
  // along the edge (follow_cone_edge); otherwise it ends here.
  ContinuationResult stop_on_cone_edge() {
    if (auto along_edge = follow_cone_edge(nodes_.back().orbit.one_sided_witness, true))
      return std::move(*along_edge);
    return stop(StopReason::no_tangent_map,
                "the orbit at " + to_text(result_.branch.back().parameter) +
                    " has an impulse on the friction cone's edge: no multipliers");
  }

  // An orbit can hold an impulse on the friction cone's edge over a range of
  // the parameter (docs/rigidbody.md), where the real map has no tangent map
  // and Newton meets its kink. From the last point (on the edge where
  // `on_edge`), the branch goes on as the fixed points of the map with the
  // impacts at flight witness `witness` forced to stick: the real map's
  // while every other impact slides, or while all stick inside the cone.
  // It is taken only where it runs along the edge: from a point on it, or
  // through an impact that starts to slide (located there as `stick_end`).
  // Back on the real map from where another impact starts to stick.
  std::optional<ContinuationResult> follow_cone_edge(int witness, bool on_edge) {
    if (forced_map_ || edge_tried_ || !problem_.stick_forced_at) return std::nullopt;
    edge_tried_ = true;  // once: where it finds no edge, it will not later
    const auto edge = problem_.stick_forced_at(witness);
    if (!edge) return std::nullopt;
    ContinuationRequest along_edge = request_;
    along_edge.start = result_.branch.back().state;
    along_edge.from = result_.branch.back().parameter;
    along_edge.max_points = request_.max_points - static_cast<int>(result_.branch.size()) + 1;
    BranchDriver follow(*edge, along_edge);
    follow.forced_map_ = true;
    follow.real_problem_ = &problem_;
    follow.entered_cone_edge_ = on_edge;
    ContinuationResult rest = follow.run_from_start();
    if (!follow.entered_cone_edge_ || rest.branch.size() < 2) return std::nullopt;
    if (follow.left_cone_edge_) {
      ContinuationRequest off_edge = request_;
      off_edge.start = rest.branch.back().state;
      off_edge.from = rest.branch.back().parameter;
      off_edge.max_points = along_edge.max_points - static_cast<int>(rest.branch.size()) + 1;
      append(rest, BranchDriver(problem_, off_edge).run_from_start());
    }
    result_.map_evaluations = map_evaluations();
    append(result_, std::move(rest));
    return std::move(result_);
  }

  // `later` continues `earlier` from its last point, which is its first
  // (kept from `later`, whose map that point is on)
  static void append(ContinuationResult& earlier, ContinuationResult later) {
    if (!later.branch.empty() && !earlier.branch.empty()) earlier.branch.pop_back();
    earlier.branch.insert(earlier.branch.end(), later.branch.begin(), later.branch.end());
    earlier.points.insert(earlier.points.end(), later.points.begin(), later.points.end());
    earlier.stop_reason = later.stop_reason;
    earlier.stop_detail = later.stop_detail;
    earlier.map_evaluations += later.map_evaluations;
  }

  ContinuationResult stop(StopReason reason, const std::string& detail) {
    result_.stop_reason = reason;
    result_.stop_detail = detail;
    return finish();
  }

  // this driver's own, the real map's bisections at a corner included
  [[nodiscard]] int map_evaluations() const {
    return corrector_.map_evaluations() + real_map_evaluations_;
  }

  ContinuationResult finish() {
    result_.map_evaluations = map_evaluations();
    return std::move(result_);
  }

  const ContinuationProblem& problem_;
  const ContinuationRequest& request_;
  BranchCorrector<Size> corrector_;
  StepControl steps_;
  BifurcationLocator<Size> locator_;
  GrazingSystem<Size> grazing_;
  // Along the friction cone's edge (follow_cone_edge): this driver runs on
  // the map with a wall's impacts forced to stick, `real_problem_` the map
  // without; its points are on the edge from `entered_cone_edge_` on, and
  // past `left_cone_edge_` the real map takes over. A driver on the real
  // map tries the edge once (`edge_tried_`).
  bool forced_map_ = false;
  const ContinuationProblem* real_problem_ = nullptr;
  bool entered_cone_edge_ = false;
  bool left_cone_edge_ = false;
  bool edge_tried_ = false;
  int real_map_evaluations_ = 0;
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
