#include <impactlab/analysis/continuation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/tools/roots.hpp>

namespace impactlab {

namespace {

// The driver's vectors for N state components: y = (x, p), N + 1 of them,
// and the grazing system's (x, p, t_g); fixed-size for N = 2 (Size = 3),
// dynamic otherwise.
template <int Size>
struct Spaces {
  static constexpr bool fixed = Size != Eigen::Dynamic;
  using Vec = Eigen::Matrix<double, Size, 1>;                                   // (x, p)
  using StateVec = Eigen::Matrix<double, fixed ? Size - 1 : Eigen::Dynamic, 1>;  // x
  using Jacobian = Eigen::Matrix<double, fixed ? Size - 1 : Eigen::Dynamic, Size>;  // [M − I | F_p]
  using Square = Eigen::Matrix<double, Size, Size>;
  using Extended = Eigen::Matrix<double, fixed ? Size + 1 : Eigen::Dynamic, 1>;  // (x, p, t_g)
  using ExtendedSquare =
      Eigen::Matrix<double, fixed ? Size + 1 : Eigen::Dynamic, fixed ? Size + 1 : Eigen::Dynamic>;
};

// |x| of the first n components (std::hypot for n = 2)
double state_norm(const double* x, int n) {
  if (n == 2) return std::hypot(x[0], x[1]);
  return Eigen::Map<const Eigen::VectorXd>(x, n).norm();
}

// λᵢλⱼ − 1 over the pairs i < j: det M − 1 for N = 2; zero where a complex
// pair crosses the unit circle (a Neimark–Sacker point) whatever N
double det_minus_one(const MonodromyMatrix& m) {
  if (m.size() == 2) return m[0][0] * m[1][1] - m[0][1] * m[1][0] - 1.0;
  const auto lambda = multipliers_of(m);
  std::complex<double> product = 1.0;
  for (std::size_t i = 0; i < lambda.size(); ++i)
    for (std::size_t j = i + 1; j < lambda.size(); ++j) product *= lambda[i] * lambda[j] - 1.0;
  return product.real();
}

Eigen::MatrixXd dense(const MonodromyMatrix& m) {
  const auto n = static_cast<Eigen::Index>(m.size());
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = m[i][j];
  return a;
}

// The walls hit, in order: the signature without its contact phases ("c+1"),
// which may appear or end along a branch without stopping it.
std::string walls_hit(const std::string& signature) {
  std::string walls;
  std::size_t begin = 0;
  while (begin < signature.size()) {
    std::size_t end = signature.find(' ', begin);
    if (end == std::string::npos) end = signature.size();
    if (end > begin && signature[begin] != 'c')
      walls += (walls.empty() ? "" : " ") + signature.substr(begin, end - begin);
    begin = end + 1;
  }
  return walls;
}

// A point on the branch, with what the next step needs.
template <int Size>
struct BranchNode {
  typename Spaces<Size>::Vec y;
  typename Spaces<Size>::Vec tangent;  // unit, pointing along the run
  OrbitEvaluation orbit;               // detailed evaluation at y
  int iterations = 0;
  double step = 0.0;                   // the arclength from the previous node
};

template <int Size>
struct NodeCorrection {
  bool converged = false;
  bool signature_changed = false;
  typename Spaces<Size>::Vec y;
  OrbitEvaluation orbit;
  typename Spaces<Size>::Jacobian jacobian;  // [M − I | F_p]
  bool has_jacobian = false;
  int iterations = 0;
};

template <int Size>
class Driver {
  using Vec = typename Spaces<Size>::Vec;
  using Node = BranchNode<Size>;
  using Correction = NodeCorrection<Size>;

 public:
  Driver(const ContinuationProblem& problem, const ContinuationRequest& request)
      : problem_(problem), request_(request) {
    n_ = static_cast<int>(problem.dimension);
    solved_point = Vec::Zero(n_ + 1);
    const double range = std::fabs(request.to - request.from);
    const double scale = range > 0.0 ? range : 1.0;
    h_initial_ = request.initial_step > 0.0 ? request.initial_step : scale / 100.0;
    h_min_ = request.min_step > 0.0 ? request.min_step : scale * 1e-7;
    h_max_ = request.max_step > 0.0 ? request.max_step : scale / 50.0;
    // the branch runs in (x, p / scale): the range is one unit of arclength
    scale_ = scale;
    h_initial_ /= scale;
    h_min_ /= scale;
    h_max_ /= scale;
    from_ = request.from / scale;
    to_ = request.to / scale;
    phase_ = problem.phase;
  }

  ContinuationResult run_from_start() {
    if (request_.start.size() != problem_.dimension) {
      result_.stop_reason = "start_not_converged";
      result_.stop_detail = "the start has " + std::to_string(request_.start.size()) +
                            " components, the orbit's state " + std::to_string(n_);
      return finish();
    }
    Correction start = correct(point(request_.start, from_), along_parameter(1.0),
                               point(request_.start, from_), {}, nullptr);
    if (!start.converged) {
      result_.stop_reason = "start_not_converged";
      result_.stop_detail = "Newton at the start parameter did not converge";
      return finish();
    }
    const double direction = request_.to >= request_.from ? 1.0 : -1.0;
    return run(start, along_parameter(direction));
  }

  ContinuationResult run_from(const OrbitPoint& x, double p, const std::vector<double>& d) {
    if (x.size() != problem_.dimension || d.size() != problem_.dimension + 1) {
      result_.stop_reason = "start_not_converged";
      result_.stop_detail = "the switching point or direction does not match the orbit's state";
      return finish();
    }
    Vec direction(n_ + 1);
    for (int i = 0; i <= n_; ++i) direction[i] = d[i];
    const Vec y0 = point(x, p / scale_);
    const double offset = std::max(h_initial_ * 0.1, 1e-3 * (1.0 + state_norm(x.data(), n_)));
    const Vec predicted = y0 + offset * direction.normalized();
    Correction start = correct(predicted, direction.normalized(), predicted, {}, nullptr);
    if (!start.converged) {
      result_.stop_reason = "start_not_converged";
      result_.stop_detail = "no orbit found off the switching point";
      return finish();
    }
    return run(start, direction);
  }

 private:
  Vec point(const OrbitPoint& x, double p) const {
    Vec y(n_ + 1);
    for (int i = 0; i < n_; ++i) y[i] = x[i];
    y[n_] = p;
    return y;
  }
  template <class Vector>
  OrbitPoint state_of(const Vector& y) const {
    return OrbitPoint(y.data(), y.data() + n_);
  }
  // the direction (0, value) in (x, p)
  Vec along_parameter(double value) const {
    Vec d = Vec::Zero(n_ + 1);
    d[n_] = value;
    return d;
  }

  OrbitEvaluation evaluate(const Vec& y, bool detailed, const ContactWindow& window) {
    ++result_.map_evaluations;
    return problem_.evaluate(state_of(y), y[n_] * scale_, phase_, detailed, window);
  }

  double parameter_step(double p) const {
    return request_.parameter_difference > 0.0 ? request_.parameter_difference
                                               : 1e-6 * (1.0 + std::fabs(p));
  }

  // ∂F/∂p ≈ (Pⁿ(x; p + h) − Pⁿ(x; p − h)) / 2h (F = Pⁿ − x, x held)
  std::optional<typename Spaces<Size>::StateVec> parameter_derivative(
      const Vec& y, const ContactWindow& window) {
    const double h = parameter_step(y[n_] * scale_) / scale_;
    Vec shifted_up = y, shifted_down = y;
    shifted_up[n_] = y[n_] + h;
    shifted_down[n_] = y[n_] - h;
    const OrbitEvaluation up = evaluate(shifted_up, false, window);
    const OrbitEvaluation down = evaluate(shifted_down, false, window);
    if (!up.completed || !down.completed) return std::nullopt;
    typename Spaces<Size>::StateVec derivative(n_);
    for (int i = 0; i < n_; ++i) derivative[i] = (up.image[i] - down.image[i]) / (2.0 * h);
    return derivative;
  }

  // c.jacobian = [M − I | F_p]
  static void set_jacobian(Correction& c, const typename Spaces<Size>::StateVec& fp, int n) {
    const MonodromyMatrix& m = c.orbit.monodromy;
    c.jacobian.resize(n, n + 1);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) c.jacobian(i, j) = m[i][j] - (i == j ? 1.0 : 0.0);
      c.jacobian(i, n) = fp[i];
    }
    c.has_jacobian = true;
  }

  // Newton on F(y) = 0, τ·(y − y_pred) = 0 from y. A run that does not
  // complete, or (with `signature`) an orbit whose impact signature differs,
  // stops it.
  Correction correct(Vec y, const Vec& tau, const Vec& y_pred, const ContactWindow& window,
                     const std::string* signature) {
    Correction c;
    double last_step = INFINITY;
    for (int iteration = 0;; ++iteration) {
      c.orbit = evaluate(y, false, window);
      c.y = y;
      c.iterations = iteration;
      if (!c.orbit.completed) return c;
      if (signature && walls_hit(c.orbit.signature) != walls_hit(*signature)) {
        c.signature_changed = true;
        return c;
      }
      typename Spaces<Size>::StateVec residual(n_);
      for (int i = 0; i < n_; ++i) residual[i] = c.orbit.image[i] - y[i];
      const double arc = tau.dot(y - y_pred);
      const double size = 1.0 + state_norm(y.data(), n_);
      const double norm = residual.norm();
      if ((norm <= request_.tolerance * size ||
           (last_step <= 1e-11 * (1.0 + y.norm()) && norm <= 100.0 * request_.tolerance * size)) &&
          std::fabs(arc) <= 1e-9 * (1.0 + y.norm())) {
        c.converged = true;
        return c;
      }
      if (iteration == request_.max_newton_iterations) return c;
      const auto fp = parameter_derivative(y, window);
      if (!fp) return c;
      set_jacobian(c, *fp, n_);
      typename Spaces<Size>::Square system(n_ + 1, n_ + 1);
      system.topRows(n_) = c.jacobian;
      system.row(n_) = tau.transpose();
      Vec right(n_ + 1);
      right.head(n_) = -residual;
      right[n_] = -arc;
      const Vec step = system.fullPivLu().solve(right);
      if (!step.allFinite()) return c;
      y += step;
      last_step = step.norm();
    }
  }

  // The branch's unit tangent at a corrected point, oriented along `along`.
  // The null vector of the N × (N + 1) Jacobian: for N = 2 the cross product
  // of its rows, otherwise the last right singular vector.
  std::optional<Vec> tangent_at(Correction& c, const Vec& along) {
    if (!c.has_jacobian) {
      const auto fp = parameter_derivative(c.y, {});
      if (!fp) return std::nullopt;
      set_jacobian(c, *fp, n_);
    }
    Vec t;
    if constexpr (Size == 3) {
      const Vec first = c.jacobian.row(0).transpose(), second = c.jacobian.row(1).transpose();
      t = first.cross(second);
    } else {
      if (!c.jacobian.allFinite()) return std::nullopt;
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(c.jacobian, Eigen::ComputeFullV);
      t = svd.matrixV().col(n_);
    }
    if (!(t.norm() > 0.0) || !t.allFinite()) return std::nullopt;
    t.normalize();
    if (t.dot(along) < 0.0) t = -t;
    return t;
  }

  BranchPoint branch_point(const Node& node, double step) const {
    BranchPoint b;
    b.parameter = node.y[n_] * scale_;
    b.state = reported_state(node.y);
    b.phase = problem_.phase;
    b.impacts = node.orbit.impacts;
    b.contact_phases = node.orbit.contact_phases;
    b.multipliers = multipliers_of(node.orbit.monodromy);
    b.stable = std::all_of(b.multipliers.begin(), b.multipliers.end(),
                           [](const std::complex<double>& m) { return std::abs(m) < 1.0; });
    b.min_impact_speed = node.orbit.min_impact_speed;
    b.min_flight_gap = node.orbit.min_flight_gap;
    b.newton_iterations = node.iterations;
    b.step = step;
    return b;
  }

  bool accept(Correction& c, const Vec& along, double step) {
    const auto tangent = tangent_at(c, along);
    if (!tangent) return false;
    Node node;
    node.y = c.y;
    node.tangent = *tangent;
    node.iterations = c.iterations;
    node.step = step;
    node.orbit = evaluate(c.y, true, {});
    if (!node.orbit.completed) return false;
    if (!nodes_.empty()) detect(nodes_.back(), node, step);
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
    const double p = node.y[n_] * scale_;
    double best_phase = phase_, best_clearance = clearance(node.orbit, 0.0);
    for (int j = 1; j < 16; ++j) {
      const double shift = 2.0 * std::numbers::pi * j / 16.0;
      const double value = clearance(node.orbit, shift / node.orbit.omega);
      if (value > best_clearance) {
        best_clearance = value;
        best_phase = std::remainder(phase_ + shift, 2.0 * std::numbers::pi);
      }
    }
    if (best_phase == phase_) return;
    const auto moved = problem_.transport(state_of(node.y), p, phase_, best_phase);
    if (!moved) return;
    const double old_phase = phase_;
    phase_ = best_phase;
    const Vec y = point(*moved, node.y[n_]);
    Correction c = correct(y, along_parameter(1.0), y, {}, nullptr);
    const auto tangent =
        c.converged ? tangent_at(c, along_parameter(node.tangent[n_])) : std::nullopt;
    OrbitEvaluation orbit = c.converged ? evaluate(c.y, true, {}) : OrbitEvaluation{};
    if (!tangent || !orbit.completed) {
      phase_ = old_phase;
      return;
    }
    node.y = c.y;
    node.tangent = *tangent;
    node.orbit = orbit;
  }

  // a time since the working section as a time since the requested one (s)
  double time_since_requested_section(double t, const OrbitEvaluation& orbit) const {
    if (phase_ == problem_.phase || !(orbit.omega > 0.0)) return t;
    double shift = std::remainder(phase_ - problem_.phase, 2.0 * std::numbers::pi);
    if (shift < 0.0) shift += 2.0 * std::numbers::pi;
    return std::fmod(t + shift / orbit.omega, orbit.span);
  }

  // the state on the requested section
  OrbitPoint reported_state(const Vec& y) const {
    if (phase_ == problem_.phase) return state_of(y);
    const auto moved = problem_.transport(state_of(y), y[n_] * scale_, phase_, problem_.phase);
    return moved ? *moved : state_of(y);
  }

  ContinuationResult run(Correction& start, const Vec& along) {
    if (!accept(start, along, 0.0)) {
      result_.stop_reason = "start_not_converged";
      result_.stop_detail = "no branch tangent at the start";
      return finish();
    }
    signature_ = nodes_.back().orbit.signature;
    double h = h_initial_;
    const double direction = to_ >= from_ ? 1.0 : -1.0;
    while (static_cast<int>(nodes_.size()) < request_.max_points) {
      const Node& last = nodes_.back();
      const Vec tau = last.tangent;
      // the end of the range: land on p = to exactly
      const double remaining = (to_ - last.y[n_]) * direction;
      if (remaining <= 1e-12 * (1.0 + std::fabs(to_))) return finish();
      if ((last.y[n_] - from_) * direction < -1e-3 * std::fabs(to_ - from_))
        return stop("left_range", "the branch turned back past the start of the range");
      const double toward_end = tau[n_] * direction;
      if (toward_end > 0.0 && h * toward_end >= remaining) {
        const double h_end = remaining / toward_end;
        Vec predicted = last.y + h_end * tau;
        predicted[n_] = to_;
        Correction c = correct(predicted, along_parameter(1.0), predicted, {}, &signature_);
        if (c.converged && accept(c, tau, h_end)) return finish();
        if (c.signature_changed && end_at_signature_change(h_end)) return finish();
        h = 0.5 * std::min(h, h_end);
        if (h < h_min_) return stop("branch_point", "the corrector fails before the end of the range");
        continue;
      }
      const Vec predicted = last.y + h * tau;
      Correction c = correct(predicted, tau, predicted, {}, &signature_);
      bool ok = c.converged;
      if (ok) {
        const auto turned = tangent_at(c, tau);
        ok = turned && turned->dot(tau) > std::cos(30.0 * std::numbers::pi / 180.0);
      }
      if (ok && accept(c, tau, h)) {
        // a gap or impact speed about to vanish: end at the grazing point
        // before Newton meets the square-root singularity
        if (grazing_ahead(h) && end_at_signature_change(h)) return finish();
        // a corrector that only creeps (steps below 1e-5 of the range for
        // 100 points: an orbit so unstable that the integrator's noise in Pⁿ
        // exceeds the tolerance): a grazing point within reach, or a stop
        stalled_ = h < 1e-5 ? stalled_ + 1 : 0;
        if (stalled_ >= 100) {
          if (end_at_signature_change(h_max_)) return finish();
          return stop("branch_point", "stalled: steps below 1e-5 of the range for 100 points");
        }
        if (c.iterations <= 3) h = std::min(1.5 * h, h_max_);
        else if (c.iterations <= 6) h = std::min(1.1 * h, h_max_);
        else h *= 0.7;
        continue;
      }
      if ((c.signature_changed || !c.converged) && end_at_signature_change(h)) return finish();
      h *= 0.5;
      if (h < h_min_ && c.signature_changed)
        return stop("signature_change", "the impact signature changes from '" + signature_ +
                                            "' to '" + c.orbit.signature +
                                            "'; no grazing point located");
      if (h < h_min_)
        return stop("branch_point", "step below the smallest: the corrector cannot pass this point");
    }
    return stop("max_points", "the branch reached the point limit");
  }

  ContinuationResult stop(const std::string& reason, const std::string& detail) {
    result_.stop_reason = reason;
    result_.stop_detail = detail;
    return finish();
  }

  ContinuationResult finish() { return std::move(result_); }

  // --- bifurcations between two consecutive points ---

  void detect(const Node& a, const Node& b, double step) {
    struct Test {
      const char* type;
      double (*function)(const MonodromyMatrix&);
    };
    static constexpr Test tests[] = {{"fold", &det_minus_identity},
                                     {"period_doubling", &det_plus_identity},
                                     {"neimark_sacker", &det_minus_one}};
    for (const Test& test : tests) {
      const double fa = test.function(a.orbit.monodromy), fb = test.function(b.orbit.monodromy);
      if (!(fa * fb < 0.0)) continue;
      if (std::string(test.type) == "neimark_sacker") {
        // a complex pair on the unit circle, not a real pair with product 1
        const auto ma = multipliers_of(a.orbit.monodromy), mb = multipliers_of(b.orbit.monodromy);
        const auto real = [](const std::vector<std::complex<double>>& m) {
          return std::all_of(m.begin(), m.end(),
                             [](const std::complex<double>& z) { return z.imag() == 0.0; });
        };
        if (real(ma) && real(mb)) continue;
      }
      BifurcationPoint point = locate(test.type, test.function, a, step, fa, fb);
      // a multiplier through +1 where the branch does not turn back in p: a
      // branch point (a symmetry-breaking pitchfork or a transcritical point)
      if (point.type == "fold" && a.tangent[n_] * b.tangent[n_] > 0.0) point.type = "branch_point";
      result_.points.push_back(point);
    }
    for (const ParameterBoundary& boundary : problem_.boundaries) locate_boundary(boundary, a, b);
    if (a.orbit.contact_phases != b.orbit.contact_phases) locate_contact_change(a, b, step);
  }

  // The number of contact phases differs between nodes a and b (reached by
  // the step `step` from a): bisection on the arclength s from a, each trial
  // point corrected onto the branch (the hyperplane through a + s τ normal to
  // τ, as the step itself), the side decided by the trial orbit's count, down
  // to a bracket of 1e-10 of the range in p (or 1e-13 in s where the branch
  // is nearly normal to p). The point is the corrected orbit at the middle of
  // the last bracket; its error estimate is the bracket in p.
  void locate_contact_change(const Node& a, const Node& b, double step) {
    BifurcationPoint point;
    point.type = b.orbit.contact_phases > a.orbit.contact_phases ? "contact_onset" : "contact_end";
    point.parameter = 0.5 * (a.y[n_] + b.y[n_]) * scale_;
    point.state = reported_state(b.y);
    point.multipliers = multipliers_of(b.orbit.monodromy);
    point.error_estimate = 0.5 * std::fabs(b.y[n_] - a.y[n_]) * scale_;
    point.note = "detected between two branch points";
    if (!request_.locate) {
      result_.points.push_back(point);
      return;
    }
    const Vec& tau = a.tangent;
    auto corrected_at = [&](double s) {
      const Vec predicted = a.y + s * tau;
      return correct(predicted, tau, predicted, {}, nullptr);
    };
    double low = 0.0, high = step;         // a's count at low, another at high
    double p_low = a.y[n_], p_high = b.y[n_];  // the corrected ends' p (range units)
    bool failed = false;
    for (int bisection = 0; bisection < 80; ++bisection) {
      if (std::fabs(p_high - p_low) <= 1e-10 || high - low <= 1e-13) break;
      const double middle = 0.5 * (low + high);
      const Correction c = corrected_at(middle);
      if (!c.converged) {
        failed = true;
        break;
      }
      if (c.orbit.contact_phases == a.orbit.contact_phases) {
        low = middle;
        p_low = c.y[n_];
      } else {
        high = middle;
        p_high = c.y[n_];
      }
    }
    const Correction c = failed ? Correction{} : corrected_at(0.5 * (low + high));
    if (c.converged) {
      point.parameter = c.y[n_] * scale_;
      point.state = reported_state(c.y);
      point.multipliers = multipliers_of(c.orbit.monodromy);
      point.error_estimate = std::fabs(p_high - p_low) * scale_;
      point.located = true;
      point.note = contact_change_note(a.orbit.contact_phases, b.orbit.contact_phases);
    } else {
      point.note = "detected; the corrector failed while locating it";
    }
    result_.points.push_back(point);
  }

  static std::string contact_change_note(int before, int after) {
    return "contact phases per orbit " + std::to_string(before) + " -> " + std::to_string(after);
  }

  // A parameter boundary crossed between nodes a and b: its root in p (TOMS
  // 748 on the boundary's own function), and the orbit corrected there at
  // fixed p from the point of the secant a–b at that p.
  void locate_boundary(const ParameterBoundary& boundary, const Node& a, const Node& b) {
    const double pa = a.y[n_] * scale_, pb = b.y[n_] * scale_;
    const double fa = boundary.value(pa), fb = boundary.value(pb);
    if (!(fa * fb < 0.0)) return;
    BifurcationPoint point;
    point.type = boundary.type;
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
    guess[n_] = point.parameter / scale_;
    Correction c = correct(guess, along_parameter(1.0), guess, {}, nullptr);
    if (c.converged) {
      point.state = reported_state(c.y);
      point.multipliers = multipliers_of(c.orbit.monodromy);
      point.located = true;
    } else {
      point.state = reported_state(guess);
      point.note += " (the orbit there interpolated: the corrector failed)";
    }
    result_.points.push_back(point);
  }

  // The root of a test function on the arclength from node a, each trial
  // point corrected onto the branch (TOMS 748).
  BifurcationPoint locate(const char* type, double (*function)(const MonodromyMatrix&),
                          const Node& a, double step, double fa, double fb) {
    BifurcationPoint point;
    point.type = type;
    std::optional<Correction> last;
    auto on_branch = [&](double s) -> double {
      const Vec predicted = a.y + s * a.tangent;
      Correction c = correct(predicted, a.tangent, predicted, {}, nullptr);
      if (!c.converged) throw std::runtime_error("corrector failed");
      const double value = function(c.orbit.monodromy);
      last = std::move(c);
      return value;
    };
    if (!request_.locate) {
      point.note = "detected (location off)";
      point.error_estimate = std::fabs(step * a.tangent[n_]) * scale_;
      point.parameter = (a.y[n_] + 0.5 * step * a.tangent[n_]) * scale_;
      return point;
    }
    try {
      std::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(
          on_branch, 0.0, step, fa, fb, boost::math::tools::eps_tolerance<double>(42), iterations);
      const double s = 0.5 * (bracket.first + bracket.second);
      on_branch(s);
      point.parameter = last->y[n_] * scale_;
      point.state = reported_state(last->y);
      point.multipliers = multipliers_of(last->orbit.monodromy);
      point.error_estimate = std::fabs(a.tangent[n_]) * (bracket.second - bracket.first) * scale_;
      point.located = true;
    } catch (const std::exception&) {
      point.parameter = (a.y[n_] + 0.5 * step * a.tangent[n_]) * scale_;
      point.error_estimate = std::fabs(step * a.tangent[n_]) * scale_;
      point.note = "detected; the corrector failed while locating it";
    }
    return point;
  }

  // --- grazing: the end of the branch where the impact signature changes ---

  bool grazing_ahead(double h) const {
    const Node& last = nodes_.back();
    if (nodes_.size() < 2) return false;
    const Node& before = nodes_[nodes_.size() - 2];
    auto vanishing = [&](double now, double earlier) {
      return std::isfinite(now) && earlier > now && now / (earlier - now) * last.step < h;
    };
    return vanishing(last.orbit.min_flight_gap, before.orbit.min_flight_gap) ||
           vanishing(last.orbit.min_impact_speed, before.orbit.min_impact_speed);
  }

  // After a failed step of length h from the last point: solve the grazing
  // system for each candidate (the lowest flight gap, the slowest impact);
  // a solution within reach ends the branch there.
  bool end_at_signature_change(double h) {
    const Node& last = nodes_.back();
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
      if (nodes_.size() < 2) return true;
      const double before = nodes_[nodes_.size() - 2].orbit.*value;
      if (!(before > now)) return false;
      return now / (before - now) * last.step < 4.0 * h;
    };
    if (last.orbit.min_flight_gap_witness >= 0 && vanishing(&OrbitEvaluation::min_flight_gap))
      candidates.push_back({last.orbit.min_flight_gap_witness, last.orbit.min_flight_gap_time,
                            "a flight extremum touches the wall"});
    if (last.orbit.slowest_impact_witness >= 0 && vanishing(&OrbitEvaluation::min_impact_speed))
      candidates.push_back({last.orbit.slowest_impact_witness, last.orbit.slowest_impact_time,
                            "an impact velocity goes to zero"});
    // the candidate whose extrapolated gap or speed vanishes soonest first
    std::optional<BifurcationPoint> best;
    double best_s = INFINITY;
    for (const Candidate& candidate : candidates) {
      // the impact section's own wall: solved on the stroboscopic map
      const bool section_wall = candidate.witness == problem_.section_witness;
      auto solved = section_wall ? solve_section_wall_grazing(last)
                                 : solve_grazing(last, candidate.witness, candidate.time, h);
      if (!solved) continue;
      const double s = last.tangent.dot(solved_point - last.y);
      if (s < -0.05 * h || s > 1.5 * h || s >= best_s) continue;
      solved->note = section_wall ? "an impact velocity goes to zero: the section's own impact "
                                    "(solved on the stroboscopic map)"
                                  : candidate.kind;
      best = solved;
      best_s = s;
    }
    if (!best) return false;
    result_.points.push_back(*best);
    result_.stop_reason = "signature_change";
    result_.stop_detail = "grazing: " + best->note;
    return true;
  }

  // A solution of the grazing system: z = (x, p, t_g) in branch units, the
  // orbit there, and Newton's last step in p (branch units).
  struct GrazingSolution {
    typename Spaces<Size>::Extended z;
    OrbitEvaluation orbit;
    double parameter_step = 0.0;
    ContactWindow window;  // the contacts suppressed (times since the section)
  };

  // Newton on z = (x, p, t_g) from the guess z, on the map `on` at section
  // phase `phase`: Pⁿ(x; p) = x with the contacts of `witness` suppressed
  // within nT/10 of the first guess of t_g, gap(t_g) = 0, gap rate(t_g) = 0;
  // central-difference Jacobian. None where a run fails, Newton does not
  // converge in 25 iterations, or t_g leaves the window.
  std::optional<GrazingSolution> newton_grazing(const ContinuationProblem& on, double phase,
                                                typename Spaces<Size>::Extended z, int witness) {
    using Vec4 = typename Spaces<Size>::Extended;
    const double time = z[n_ + 1];
    const double span = problem_.forcing_period_at_p;
    const double half_width = span > 0.0 ? 0.1 * span : 0.1;
    const ContactWindow window{witness, time - half_width, time + half_width};
    auto residual_of = [&](const Vec4& y, OrbitEvaluation* orbit) -> std::optional<Vec4> {
      ++result_.map_evaluations;
      OrbitEvaluation e = on.evaluate(state_of(y), y[n_] * scale_, phase, false, window);
      if (!e.completed) return std::nullopt;
      const GapSample gap = on.gap_at(state_of(y), y[n_] * scale_, phase, window, y[n_ + 1]);
      if (!gap.completed) return std::nullopt;
      if (orbit) *orbit = e;
      Vec4 r(n_ + 2);
      for (int i = 0; i < n_; ++i) r[i] = e.image[i] - y[i];
      r[n_] = gap.value;
      r[n_ + 1] = gap.rate;
      return r;
    };
    double last_parameter_step = INFINITY;
    for (int iteration = 0; iteration < 25; ++iteration) {
      OrbitEvaluation orbit;
      const auto r = residual_of(z, &orbit);
      if (!r) return std::nullopt;
      const double size = 1.0 + state_norm(z.data(), n_);
      if (r->norm() <= request_.tolerance * size && iteration > 0 &&
          std::fabs(last_parameter_step) <= 1e-11 * (1.0 + std::fabs(z[n_])))
        return GrazingSolution{z, orbit, last_parameter_step, window};
      typename Spaces<Size>::ExtendedSquare jacobian(n_ + 2, n_ + 2);
      for (int j = 0; j < n_ + 2; ++j) {
        const double dz = 1e-7 * (1.0 + std::fabs(z[j]));
        Vec4 up = z, down = z;
        up[j] += dz;
        down[j] -= dz;
        const auto ru = residual_of(up, nullptr), rd = residual_of(down, nullptr);
        if (!ru || !rd) return std::nullopt;
        jacobian.col(j) = (*ru - *rd) / (2.0 * dz);
      }
      const Vec4 step = jacobian.fullPivLu().solve(-*r);
      if (!step.allFinite()) return std::nullopt;
      z += step;
      last_parameter_step = step[n_];
      if (std::fabs(z[n_ + 1] - time) > half_width) return std::nullopt;  // left the window
    }
    return std::nullopt;
  }

  // The located point of a grazing solution: its parameter, multipliers and
  // error estimate (Newton's last step in p, at least the tolerance).
  BifurcationPoint grazing_point(const GrazingSolution& solved, int witness) const {
    BifurcationPoint point;
    point.type = "grazing";
    point.parameter = solved.z[n_] * scale_;
    point.multipliers = multipliers_of(solved.orbit.monodromy);
    point.error_estimate = std::max(std::fabs(solved.parameter_step) * scale_,
                                    request_.tolerance * (1.0 + std::fabs(point.parameter)));
    point.graze_witness = witness;
    point.located = true;
    return point;
  }

  // The grazing system on the branch's own map, from the last point moved
  // half the failed step along the branch, t_g from `time`.
  std::optional<BifurcationPoint> solve_grazing(const Node& last, int witness, double time,
                                                double h) {
    typename Spaces<Size>::Extended z(n_ + 2);
    z.head(n_ + 1) = last.y + 0.5 * h * last.tangent;
    z[n_ + 1] = time;
    const auto solved = newton_grazing(problem_, phase_, z, witness);
    if (!solved) return std::nullopt;
    BifurcationPoint point = grazing_point(*solved, witness);
    point.state = reported_state(solved->z.head(n_ + 1));
    point.graze_time = time_since_requested_section(solved->z[n_ + 1], solved->orbit);
    solved_point = solved->z.head(n_ + 1);
    return point;
  }

  // The impact section: the impact with the section's own wall grazes (the
  // map ends there). The same grazing system, solved on the stroboscopic map
  // problem_.strobe at the phase half a forcing period after the last
  // point's impact (so that the graze, one orbit after that impact, at
  // t_g = nT − T/2, lies half a period from the section), from the last
  // point carried there along the virtual orbit. Back on the
  // impact section the point is (φ, q̇⁻) = (phase + ω (t_g − nT), q̇(t_g)):
  // the graze is the section's own impact, touched at the section
  // (graze_time 0).
  std::optional<BifurcationPoint> solve_section_wall_grazing(const Node& last) {
    if (!problem_.strobe || !problem_.to_strobe || !(last.orbit.omega > 0.0)) return std::nullopt;
    const ContinuationProblem& strobe = *problem_.strobe;
    const double p = last.y[n_] * scale_;
    const double phase = last.y[0] + std::numbers::pi;
    const auto carried = problem_.to_strobe(state_of(last.y), p, phase);
    if (!carried) return std::nullopt;
    typename Spaces<Size>::Extended z(n_ + 2);
    for (int i = 0; i < n_; ++i) z[i] = (*carried)[i];
    z[n_] = last.y[n_];
    z[n_ + 1] = last.orbit.span - std::numbers::pi / last.orbit.omega;
    const int witness = problem_.section_witness;
    const auto solved = newton_grazing(strobe, phase, z, witness);
    if (!solved) return std::nullopt;
    const double t_g = solved->z[n_ + 1];
    const GapSample at =
        strobe.gap_at(state_of(solved->z), solved->z[n_] * scale_, phase, solved->window, t_g);
    if (!at.completed || at.state.size() < 2) return std::nullopt;
    BifurcationPoint located = grazing_point(*solved, witness);
    located.state = {phase + solved->orbit.omega * (t_g - solved->orbit.span), at.state[1]};
    located.graze_time = 0.0;
    solved_point = point(located.state, solved->z[n_]);
    return located;
  }

  const ContinuationProblem& problem_;
  const ContinuationRequest& request_;
  double h_initial_, h_min_, h_max_;
  double scale_ = 1.0;        // the parameter's unit of arclength (the range)
  double from_ = 0.0, to_ = 1.0;  // the range in that unit
  int stalled_ = 0;           // consecutive points reached by tiny steps
  double phase_ = 0.0;        // rad: the section the branch is computed on (moved off impacts)
  int n_ = 2;                 // N: the state's components on the section
  Vec solved_point;           // the last grazing solution, in branch units
  std::vector<Node> nodes_;
  std::string signature_;
  ContinuationResult result_;
};

}  // namespace

ContinuationResult continue_branch(const ContinuationProblem& problem,
                                   const ContinuationRequest& request) {
  if (problem.dimension == 2) return Driver<3>(problem, request).run_from_start();
  return Driver<Eigen::Dynamic>(problem, request).run_from_start();
}

ContinuationResult continue_branch_from(const ContinuationProblem& problem,
                                        const ContinuationRequest& request,
                                        const OrbitPoint& x, double p,
                                        const std::vector<double>& direction) {
  if (problem.dimension == 2) return Driver<3>(problem, request).run_from(x, p, direction);
  return Driver<Eigen::Dynamic>(problem, request).run_from(x, p, direction);
}

std::vector<std::complex<double>> multipliers_of(const MonodromyMatrix& m) {
  if (m.size() == 2) {
    const double half_trace = 0.5 * (m[0][0] + m[1][1]);
    const double determinant = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    const std::complex<double> root =
        std::sqrt(std::complex<double>(half_trace * half_trace - determinant));
    std::complex<double> a = half_trace + root, b = half_trace - root;
    if (std::abs(b) > std::abs(a)) std::swap(a, b);
    return {a, b};
  }
  const Eigen::MatrixXd a = dense(m);
  std::vector<std::complex<double>> values(m.size(), {std::numeric_limits<double>::quiet_NaN(), 0.0});
  if (!a.allFinite()) return values;
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(a, false);
  if (solver.info() != Eigen::Success) return values;
  for (std::size_t i = 0; i < m.size(); ++i) values[i] = solver.eigenvalues()[static_cast<Eigen::Index>(i)];
  std::sort(values.begin(), values.end(), [](const auto& x, const auto& y) {
    if (std::abs(x) != std::abs(y)) return std::abs(x) > std::abs(y);
    return x.imag() > y.imag();
  });
  return values;
}

double det_minus_identity(const MonodromyMatrix& m) {
  if (m.size() == 2) return (m[0][0] - 1.0) * (m[1][1] - 1.0) - m[0][1] * m[1][0];
  const Eigen::MatrixXd a = dense(m);
  return (a - Eigen::MatrixXd::Identity(a.rows(), a.cols())).fullPivLu().determinant();
}

double det_plus_identity(const MonodromyMatrix& m) {
  if (m.size() == 2) return (m[0][0] + 1.0) * (m[1][1] + 1.0) - m[0][1] * m[1][0];
  const Eigen::MatrixXd a = dense(m);
  return (a + Eigen::MatrixXd::Identity(a.rows(), a.cols())).fullPivLu().determinant();
}

OrbitPoint eigenvector_for(const MonodromyMatrix& m, double multiplier) {
  if (m.size() != 2) {
    // the right singular vector of M − λI of the smallest singular value
    Eigen::MatrixXd a = dense(m);
    a.diagonal().array() -= multiplier;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
    const Eigen::VectorXd v = svd.matrixV().col(a.cols() - 1);
    return OrbitPoint(v.data(), v.data() + v.size());
  }
  // (M − λI) v = 0: v ⟂ the larger row of M − λI
  const double a = m[0][0] - multiplier, b = m[0][1];
  const double c = m[1][0], d = m[1][1] - multiplier;
  OrbitPoint v = std::hypot(a, b) >= std::hypot(c, d) ? OrbitPoint{-b, a} : OrbitPoint{-d, c};
  const double norm = std::hypot(v[0], v[1]);
  if (norm > 0.0) v = {v[0] / norm, v[1] / norm};
  return v;
}

}  // namespace impactlab
