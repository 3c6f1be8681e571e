#include <impactlab/analysis/curve_continuation.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <boost/math/tools/toms748_solve.hpp>

#include <impactlab/analysis/bifurcation_location.hpp>
#include <impactlab/analysis/chatter_onset.hpp>
#include <impactlab/analysis/dense_solve.hpp>
#include <impactlab/analysis/floquet_multipliers.hpp>
#include <impactlab/analysis/grazing_normal_form.hpp>
#include <impactlab/analysis/impact_signature.hpp>

namespace impactlab {

namespace {

using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

// The dominant multiplier where it is real; NaN where it is one of a complex
// pair (the eigenvalue rule does not apply there, and no sign is watched).
double dominant_real_multiplier(const MonodromyMatrix& m) {
  const std::vector<std::complex<double>> multipliers = multipliers_of(m);
  if (multipliers.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::complex<double> dominant = multipliers.front();
  if (std::fabs(dominant.imag()) > 1e-12 * (1.0 + std::abs(dominant)))
    return std::numeric_limits<double>::quiet_NaN();
  return dominant.real();
}

// The eigenvalue rule's thresholds on λ₁ (grazing_normal_form.hpp,
// eigenvalue_rule): period adding below 1/4, with chaotic windows up to 2/3,
// chaos above.
double dominant_multiplier_past_quarter(const MonodromyMatrix& m) {
  return dominant_real_multiplier(m) - 0.25;
}
double dominant_multiplier_past_two_thirds(const MonodromyMatrix& m) {
  return dominant_real_multiplier(m) - 2.0 / 3.0;
}

// The residual of the defining system at one point, and the orbit it ran.
struct Evaluation {
  bool completed = false;
  Vector residual;  // F (N), then det(M ∓ I) or gap and gap rate
  OrbitEvaluation orbit;
};

struct Corrected {
  bool converged = false;
  Vector z;
  Evaluation at;
  Matrix jacobian;  // of the residual, at the last iterate before z
  int iterations = 0;
};

class CurveDriver {
 public:
  CurveDriver(const TwoParameterProblem& problem, const CurveRequest& request)
      : problem_(problem), request_(request) {
    grazing_ = request.type == CurveType::grazing;
    contact_ = request.type == CurveType::contact_onset || request.type == CurveType::contact_end;
    boundary_ = request.type == CurveType::contact_boundary;
    chatter_ = request.type == CurveType::chatter_onset;
    at_start_ = problem.at(request.from2);
    n_ = static_cast<int>(at_start_.dimension);
    p1_ = n_;
    p2_ = n_ + 1;
    tg_ = n_ + 2;
    size_ = grazing_ ? n_ + 3 : n_ + 2;
    scale1_ = std::fabs(request.to1 - request.from1);
    scale2_ = std::fabs(request.to2 - request.from2);
    if (!(scale1_ > 0.0)) scale1_ = 1.0;
    if (!(scale2_ > 0.0)) scale2_ = 1.0;
    h_initial_ = request.initial_step > 0.0 ? request.initial_step : 0.01;
    h_min_ = request.min_step > 0.0 ? request.min_step : 1e-7;
    h_max_ = request.max_step > 0.0 ? request.max_step : 0.02;
    requested_phase_ = at_start_.phase;
    phase_ = requested_phase_;
    // the scale of t_g in the arclength: the orbit's span at the start
    time_scale_ = at_start_.forcing_period_at_p > 0.0 ? at_start_.forcing_period_at_p : 1.0;
    window_half_width_ = 0.1 * time_scale_;
  }

  CurveResult run() {
    result_.type = request_.type;
    if (request_.state.size() != at_start_.dimension)
      return stop(StopReason::start_not_converged, "the start's state does not match the orbit's");
    if (chatter_) return run_chatter_onset();
    Vector z = Vector::Zero(size_);
    for (int i = 0; i < n_; ++i) z[i] = request_.state[i];
    z[p1_] = request_.p1 / scale1_;
    z[p2_] = request_.from2 / scale2_;
    if (grazing_) {
      if (request_.graze_witness < 0 || !std::isfinite(request_.graze_time))
        return stop(StopReason::start_not_converged,
                    "a grazing curve needs the graze time and wall");
      z[tg_] = request_.graze_time / time_scale_;
      window_center_ = request_.graze_time;
    }
    if (boundary_ && !boundary_of(at_start_))
      return stop(StopReason::start_not_converged,
                  "the scene has no parameter boundary named " +
                      std::string(to_string(request_.type)));
    choose_section(z);
    // the start: corrected at p₂ = from2
    Vector fixed_p2 = Vector::Zero(size_);
    fixed_p2[p2_] = 1.0;
    Corrected start = correct(z, fixed_p2, z);
    if (contact_ && start.at.orbit.completed && !std::isfinite(start.at.orbit.landing_push))
      return stop(StopReason::start_not_converged,
                  "the orbit has no landing with a push on the mass at rest (a contact curve "
                  "needs a system with a stuck mode)");
    if (!start.converged)
      return stop(StopReason::start_not_converged, "Newton at the located point did not converge");
    const double direction2 = request_.to2 >= request_.from2 ? 1.0 : -1.0;
    Vector along = Vector::Zero(size_);
    along[p2_] = direction2;
    auto tangent = tangent_of(start.jacobian, along);
    if (!tangent) return stop(StopReason::start_not_converged, "no curve tangent at the start");
    accept(start, *tangent, 0.0);

    const double from2 = request_.from2 / scale2_, to2 = request_.to2 / scale2_;
    const double low1 = std::min(request_.from1, request_.to1) / scale1_;
    const double high1 = std::max(request_.from1, request_.to1) / scale1_;
    double h = h_initial_;
    while (static_cast<int>(result_.curve.size()) < request_.max_points) {
      const Vector last = z_;
      const Vector tau = tangent_;
      const double remaining = (to2 - last[p2_]) * direction2;
      if (remaining <= 1e-12 * (1.0 + std::fabs(to2))) return finish();
      if (last[p1_] < low1 - 1e-9 || last[p1_] > high1 + 1e-9)
        return stop(StopReason::left_range, "the curve left the first parameter's range");
      if ((last[p2_] - from2) * direction2 < -1e-9)
        return stop(StopReason::left_range,
                    "the curve turned back past the second parameter's start");
      const double toward_end = tau[p2_] * direction2;
      if (toward_end > 0.0 && h * toward_end >= remaining) {
        const double h_end = remaining / toward_end;
        Vector predicted = last + h_end * tau;
        predicted[p2_] = to2;
        Corrected c = correct(predicted, fixed_p2, predicted);
        if (c.converged && grazes_between(c)) {
          if (auto graze = meets_graze(h_end)) return stop_at(std::move(*graze));
        } else if (c.converged) {
          const auto t = tangent_of(c.jacobian, tau);
          if (t) {
            accept(c, *t, h_end);
            return finish();
          }
        }
        h = 0.5 * std::min(h, h_end);
        if (h < h_min_) return stop_below_smallest_step(h_end);
        continue;
      }
      const Vector predicted = last + h * tau;
      Corrected c = correct(predicted, tau, predicted);
      if (c.converged && grazes_between(c)) {
        if (auto graze = meets_graze(h)) return stop_at(std::move(*graze));
      } else {
        std::optional<Vector> t;
        if (c.converged) t = tangent_of(c.jacobian, tau);
        if (t && t->dot(tau) > std::cos(30.0 * std::numbers::pi / 180.0)) {
          accept(c, *t, h);
          if (c.iterations <= 3) h = std::min(1.5 * h, h_max_);
          else if (c.iterations > 6) h *= 0.7;
          continue;
        }
      }
      h *= 0.5;
      if (h < h_min_) return stop_below_smallest_step(2.0 * h);
    }
    return stop(StopReason::max_points, "the curve reached the point limit");
  }

 private:
  double p1_of(const Vector& z) const { return z[p1_] * scale1_; }
  double p2_of(const Vector& z) const { return z[p2_] * scale2_; }

  // the problem's parameter boundary that a boundary curve follows (its name
  // is the curve type's); none where the scene has none of that name
  const ParameterBoundary* boundary_of(const ContinuationProblem& at) const {
    const auto found = std::find_if(
        at.boundaries.begin(), at.boundaries.end(),
        [&](const ParameterBoundary& b) { return b.name == to_string(request_.type); });
    return found == at.boundaries.end() ? nullptr : &*found;
  }
  OrbitPoint state_of(const Vector& z) const { return OrbitPoint(z.data(), z.data() + n_); }

  ContactWindow window() const {
    if (!grazing_) return {};
    return {request_.graze_witness, window_center_ - window_half_width_,
            window_center_ + window_half_width_};
  }

  Evaluation evaluate(const Vector& z) {
    ++result_.map_evaluations;
    Evaluation e;
    const ContinuationProblem at = problem_.at(p2_of(z));
    e.orbit = at.evaluate(state_of(z), p1_of(z), phase_, false, window());
    if (!e.orbit.completed) return e;
    e.residual.resize(size_ - 1);
    for (int i = 0; i < n_; ++i) e.residual[i] = e.orbit.image[i] - z[i];
    if (grazing_) {
      const GapSample gap = at.gap_at(state_of(z), p1_of(z), phase_, window(), z[tg_] * time_scale_);
      if (!gap.completed) return e;
      e.residual[n_] = gap.value;
      e.residual[n_ + 1] = gap.rate;
    } else if (contact_) {
      // the push on the mass at rest at its landing (contact_landing.hpp)
      e.residual[n_] = e.orbit.landing_push;
    } else if (boundary_) {
      // the scene's boundary, a function of the parameters alone
      const ParameterBoundary* boundary = boundary_of(at);
      if (!boundary) return e;
      e.residual[n_] = boundary->value(p1_of(z));
    } else {
      e.residual[n_] = multiplier_condition(e.orbit.monodromy);
    }
    e.completed = e.residual.allFinite();
    return e;
  }

  // The onset of complete chatter, followed in p₂ (solve_chatter_onset,
  // chatter_onset.hpp, at each p₂): the map is not smooth at the onset, so
  // no Newton on the orbit and no arclength; p₁ and the release flight's
  // state are predicted from the last two points, and the step in p₂ halves
  // where the solve fails. A curve that turns back in p₂ ends there.
  CurveResult run_chatter_onset() {
    const double direction2 = request_.to2 >= request_.from2 ? 1.0 : -1.0;
    const double low1 = std::min(request_.from1, request_.to1);
    const double high1 = std::max(request_.from1, request_.to1);
    const auto solve_at = [&](double p2, const OrbitPoint& x, double p1) {
      const ContinuationProblem at = problem_.at(p2);
      const OrbitAt orbit_at = [&](const OrbitPoint& state, double p) {
        ++result_.map_evaluations;
        return at.evaluate(state, p, requested_phase_, false, {});
      };
      const double offset = 1e-6 * scale1_;
      return solve_chatter_onset(orbit_at, x, p1 - offset, x, p1);
    };
    const auto accept_onset = [&](const ChatterOnset& onset, double p2, double step) {
      CurvePoint point;
      point.p1 = onset.parameter;
      point.p2 = p2;
      point.state = onset.state;
      point.multipliers = multipliers_of(onset.orbit.monodromy);
      point.impacts = onset.orbit.impacts;
      point.newton_iterations = 0;  // no Newton: secant steps in p₁ alone
      point.step = step;
      result_.curve.push_back(std::move(point));
    };
    const ChatterOnset start = solve_at(request_.from2, request_.state, request_.p1);
    if (!start.found)
      return stop(StopReason::start_not_converged,
                  "no onset of complete chatter at the located point: its chatter does not "
                  "resolve enough impacts (chatter_onset.hpp)");
    accept_onset(start, request_.from2, 0.0);
    double h = h_initial_ * scale2_;
    while (static_cast<int>(result_.curve.size()) < request_.max_points) {
      const CurvePoint& last = result_.curve.back();
      if (last.p1 < low1 || last.p1 > high1)
        return stop(StopReason::left_range, "the curve left the first parameter's range");
      const double remaining = (request_.to2 - last.p2) * direction2;
      if (remaining <= 1e-12 * (1.0 + std::fabs(request_.to2))) return finish();
      const double step = std::min(h, remaining);
      const double p2 = remaining <= h ? request_.to2 : last.p2 + direction2 * step;
      // the prediction: along the last two points
      double p1 = last.p1;
      OrbitPoint x = last.state;
      if (result_.curve.size() >= 2) {
        const CurvePoint& before = result_.curve[result_.curve.size() - 2];
        const double fraction = (p2 - last.p2) / (last.p2 - before.p2);
        p1 += (last.p1 - before.p1) * fraction;
        for (std::size_t i = 0; i < x.size(); ++i) x[i] += (last.state[i] - before.state[i]) * fraction;
      }
      const ChatterOnset onset = solve_at(p2, x, p1);
      if (onset.found) {
        accept_onset(onset, p2, step / scale2_);
        h = std::min(1.5 * h, h_max_ * scale2_);
        continue;
      }
      h *= 0.5;
      if (h < h_min_ * scale2_)
        return stop(StopReason::branch_point,
                    "step below the smallest: the onset of complete chatter is not found "
                    "past this point");
    }
    return stop(StopReason::max_points, "the curve reached the point limit");
  }

  // The condition on the multipliers of a fold, period-doubling or
  // Neimark–Sacker curve.
  double multiplier_condition(const MonodromyMatrix& m) const {
    if (request_.type == CurveType::period_doubling) return det_plus_identity(m);
    if (request_.type == CurveType::neimark_sacker) return neimark_sacker_test(m);
    return det_minus_identity(m);
  }

  // Whether the curve ends where its orbit grazes: fold and period-doubling
  // curves.
  bool stops_at_grazes() const {
    return request_.type == CurveType::fold || request_.type == CurveType::period_doubling;
  }

  // ∂residual/∂z: the orbit rows' state part from the monodromy, the rest by
  // central differences
  std::optional<Matrix> jacobian(const Vector& z, const Evaluation& at) {
    Matrix j(size_ - 1, size_);
    for (int k = 0; k < size_; ++k) {
      const double dz = (k < n_ || k == tg_ ? 1e-7 : 1e-6) * (1.0 + std::fabs(z[k]));
      Vector up = z, down = z;
      up[k] += dz;
      down[k] -= dz;
      const Evaluation eu = evaluate(up), ed = evaluate(down);
      if (!eu.completed || !ed.completed) return std::nullopt;
      j.col(k) = (eu.residual - ed.residual) / (2.0 * dz);
    }
    const MonodromyMatrix& m = at.orbit.monodromy;
    for (int row = 0; row < n_; ++row)
      for (int column = 0; column < n_; ++column)
        j(row, column) = m[row][column] - (row == column ? 1.0 : 0.0);
    return j;
  }

  // Newton on (residual, τ·(z − z_pred)) = 0 from z.
  Corrected correct(Vector z, const Vector& tau, const Vector& z_pred) {
    Corrected c;
    double last_step = INFINITY;
    for (int iteration = 0;; ++iteration) {
      c.at = evaluate(z);
      c.z = z;
      c.iterations = iteration;
      if (!c.at.completed) return c;
      const double size = 1.0 + (n_ == 2 ? std::hypot(z[0], z[1]) : z.head(n_).norm());
      const double arc = tau.dot(z - z_pred);
      const double orbit_residual = c.at.residual.head(n_).norm();
      const double condition_residual = c.at.residual.tail(size_ - 1 - n_).norm();
      const bool small_step = last_step <= 1e-11 * (1.0 + z.norm());
      if (c.jacobian.size() > 0 && std::fabs(arc) <= 1e-9 * (1.0 + z.norm()) &&
          ((orbit_residual <= request_.tolerance * size &&
            condition_residual <= request_.tolerance * size && last_step <= 1e-9 * (1.0 + z.norm())) ||
           (small_step && orbit_residual <= 100.0 * request_.tolerance * size))) {
        c.converged = true;
        return c;
      }
      if (iteration == request_.max_newton_iterations) return c;
      const auto j = jacobian(z, c.at);
      if (!j) return c;
      c.jacobian = *j;
      Matrix system(size_, size_);
      system.topRows(size_ - 1) = *j;
      system.row(size_ - 1) = tau.transpose();
      Vector right(size_);
      right.head(size_ - 1) = -c.at.residual;
      right[size_ - 1] = -arc;
      const Vector step = full_pivot_lu_solve(system, right);
      if (!step.allFinite()) return c;
      z += step;
      last_step = step.norm();
      if (grazing_ && std::fabs(z[tg_] * time_scale_ - window_center_) > window_half_width_)
        return c;  // the graze left the suppression window
    }
  }

  // The unit null vector of the (size − 1) × size Jacobian, oriented along `along`.
  std::optional<Vector> tangent_of(const Matrix& j, const Vector& along) const {
    if (j.rows() != size_ - 1) return std::nullopt;
    Vector t = last_right_singular_vector(j);
    if (!t.allFinite() || !(t.norm() > 0.0)) return std::nullopt;
    t.normalize();
    if (t.dot(along) < 0.0) t = -t;
    return t;
  }

  void accept(const Corrected& c, const Vector& tangent, double step) {
    if (!result_.curve.empty()) detect_codimension_two(z_, tangent_, step, c);
    // the normal form only where λ₁ is real: with a complex pair the rule
    // does not apply and K is not formed (the monodromy from the section and
    // the one from the touch are similar: the same multipliers)
    std::optional<GrazingNormalForm> form;
    if (grazing_ && request_.normal_forms &&
        std::isfinite(dominant_real_multiplier(c.at.orbit.monodromy))) {
      form = normal_form_at(c.z);
      if (!result_.curve.empty()) detect_kick_sign_change(z_, tangent_, step, form);
    }
    if (request_.type == CurveType::fold && !result_.curve.empty())
      detect_cusp(z_, tangent_, step, tangent);
    double flip = std::numeric_limits<double>::quiet_NaN();
    if (request_.type == CurveType::period_doubling) {
      flip = flip_coefficient(c);
      if (!result_.curve.empty()) detect_degenerate_flip(z_, tangent_, step, flip);
    }
    z_ = c.z;
    tangent_ = tangent;
    CurvePoint point = point_of(c);
    point.newton_iterations = c.iterations;
    point.step = step;
    if (grazing_) window_center_ = c.z[tg_] * time_scale_;
    last_signature_ = c.at.orbit.signature;
    last_flip_coefficient_ = flip;
    last_form_ = std::move(form);
    const auto watched = watched_conditions();
    for (std::size_t k = 0; k < watched.size(); ++k)
      last_tests_[k] = watched[k].function(c.at.orbit.monodromy);
    result_.curve.push_back(point);
  }

  // The curve point of a corrected z: its parameters, multipliers, graze
  // time and state, both on the requested section.
  CurvePoint point_of(const Corrected& c) const {
    CurvePoint point;
    point.p1 = p1_of(c.z);
    point.p2 = p2_of(c.z);
    point.multipliers = multipliers_of(c.at.orbit.monodromy);
    point.impacts = c.at.orbit.impacts;
    if (grazing_) point.graze_time = graze_time_on_requested(c.z[tg_] * time_scale_, c.at.orbit);
    point.state = state_of(c.z);
    if (phase_ != requested_phase_) {
      const auto moved = problem_.at(point.p2).transport(state_of(c.z), point.p1, phase_,
                                                          requested_phase_);
      if (moved) point.state = *moved;
    }
    return point;
  }

  // A graze time on the working section (s since it) as a time since the
  // requested section.
  double graze_time_on_requested(double time, const OrbitEvaluation& orbit) const {
    const double shift = std::remainder(phase_ - requested_phase_, 2.0 * std::numbers::pi);
    const double delay = (shift < 0.0 ? shift + 2.0 * std::numbers::pi : shift) / orbit.omega;
    return std::fmod(time + delay, orbit.span);
  }

  // Whether a fold or period-doubling curve's corrected point c hits other
  // walls than the last point (contact phases aside, as on a branch): the
  // orbit grazed between them (a wall touched in flight, or an impact's speed
  // gone to zero), and c is an orbit of another family.
  bool grazes_between(const Corrected& c) const {
    return stops_at_grazes() && !result_.curve.empty() &&
           !same_walls_hit(c.at.orbit.signature, last_signature_);
  }

  // A solution of the system of the curve's condition and a graze: z = (x,
  // p₁, p₂, t_g) in curve units, the virtual orbit there, Newton's last step.
  struct GrazeMeeting {
    Vector z;
    OrbitEvaluation orbit;
    double last_step = 0.0;
  };

  // Where the curve meets a grazing curve, within reach of the last point
  // (the arclength h ahead, where the signature changed): for each candidate
  // of the last orbit (its lowest flight gap, its slowest impact; the impact
  // section's own wall apart), the curve's condition solved with the
  // grazing system's (gap(t_g) = 0, gap rate(t_g) = 0, the wall's contacts
  // near t_g suppressed); the solution nearest along the curve.
  std::optional<CodimensionTwoPoint> meets_graze(double h) {
    struct Candidate {
      int witness;
      double time;
      const char* kind;
    };
    std::vector<Candidate> candidates;
    const ContinuationProblem at = problem_.at(p2_of(z_));
    // the last orbit again, its flight gaps sampled
    const OrbitEvaluation last = at.evaluate(state_of(z_), p1_of(z_), phase_, true, window());
    ++result_.map_evaluations;
    if (!last.completed) return std::nullopt;
    if (last.min_flight_gap_witness >= 0 && last.min_flight_gap_witness != at.section_witness)
      candidates.push_back({last.min_flight_gap_witness, last.min_flight_gap_time,
                            "a flight extremum touches the wall"});
    if (last.slowest_impact_witness >= 0 && last.slowest_impact_witness != at.section_witness)
      candidates.push_back({last.slowest_impact_witness, last.slowest_impact_time,
                            "an impact velocity goes to zero"});
    std::optional<CodimensionTwoPoint> best;
    double best_s = INFINITY;
    for (const Candidate& candidate : candidates) {
      const auto solved = solve_graze_meeting(candidate.witness, candidate.time);
      if (!solved) continue;
      const double s = tangent_.dot(solved->z.head(size_) - z_);
      if (s < -0.05 * h || s > 1.5 * h || s >= best_s) continue;
      best_s = s;
      CodimensionTwoPoint point;
      point.type = request_.type == CurveType::fold ? CodimensionTwoType::grazing_fold
                                                    : CodimensionTwoType::grazing_period_doubling;
      Corrected at;
      at.z = solved->z.head(size_);
      at.at.orbit = solved->orbit;
      const CurvePoint on = point_of(at);
      point.p1 = on.p1;
      point.p2 = on.p2;
      point.state = on.state;
      point.multipliers = on.multipliers;
      point.graze_time =
          graze_time_on_requested(solved->z[size_] * time_scale_, solved->orbit);
      point.graze_witness = candidate.witness;
      point.error_estimate =
          solved->last_step * std::max(scale1_, scale2_) +
          request_.tolerance * (1.0 + std::max(std::fabs(on.p1), std::fabs(on.p2)));
      point.located = true;
      point.note = candidate.kind;
      best = std::move(point);
    }
    return best;
  }

  // Newton on (F, the curve's condition, gap(t_g), gap rate(t_g)) = 0 in
  // (x, p₁, p₂, t_g) from the last point, the contacts of `witness`
  // suppressed within nT/10 of the guess t₀ (s since the working section);
  // central-difference Jacobian. None where a run fails, Newton does not
  // converge in 25 iterations, or t_g leaves the window.
  std::optional<GrazeMeeting> solve_graze_meeting(int witness, double t0) {
    const int size = size_ + 1, tg = size_;
    const ContactWindow window{witness, t0 - window_half_width_, t0 + window_half_width_};
    const auto residual = [&](const Vector& y, OrbitEvaluation* orbit) -> std::optional<Vector> {
      ++result_.map_evaluations;
      const ContinuationProblem at = problem_.at(p2_of(y));
      OrbitEvaluation o = at.evaluate(state_of(y), p1_of(y), phase_, false, window);
      if (!o.completed) return std::nullopt;
      const GapSample gap = at.gap_at(state_of(y), p1_of(y), phase_, window, y[tg] * time_scale_);
      if (!gap.completed) return std::nullopt;
      Vector r(size);
      for (int i = 0; i < n_; ++i) r[i] = o.image[i] - y[i];
      r[n_] = multiplier_condition(o.monodromy);
      r[n_ + 1] = gap.value;
      r[n_ + 2] = gap.rate;
      if (!r.allFinite()) return std::nullopt;
      if (orbit) *orbit = std::move(o);
      return r;
    };
    GrazeMeeting solved;
    solved.z = Vector(size);
    solved.z.head(size_) = z_;
    solved.z[tg] = t0 / time_scale_;
    double last_step = INFINITY;
    for (int iteration = 0; iteration <= 25; ++iteration) {
      const auto r = residual(solved.z, &solved.orbit);
      if (!r) return std::nullopt;
      const double scale = 1.0 + solved.z.head(n_).norm();
      if (r->norm() <= request_.tolerance * scale && last_step <= 1e-9 * (1.0 + solved.z.norm())) {
        solved.last_step = last_step;
        return solved;
      }
      Matrix j(size, size);
      for (int k = 0; k < size; ++k) {
        const double dz = (k < n_ || k == tg ? 1e-7 : 1e-6) * (1.0 + std::fabs(solved.z[k]));
        Vector up = solved.z, down = solved.z;
        up[k] += dz;
        down[k] -= dz;
        const auto ru = residual(up, nullptr), rd = residual(down, nullptr);
        if (!ru || !rd) return std::nullopt;
        j.col(k) = (*ru - *rd) / (2.0 * dz);
      }
      const Vector step = full_pivot_lu_solve(j, -*r);
      if (!step.allFinite()) return std::nullopt;
      solved.z += step;
      last_step = step.norm();
      if (std::fabs(solved.z[tg] * time_scale_ - t0) > window_half_width_) return std::nullopt;
    }
    return std::nullopt;
  }

  // A second condition watched along a grazing curve: the virtual orbit's
  // multiplier through −1 or +1, where the grazing curve meets a period
  // doubling or a fold curve of the orbit it grazes; its dominant multiplier
  // λ₁ through a threshold of the eigenvalue rule, where the predicted
  // scenario past the graze changes (reported only where the rule applies
  // there, rule_applies; `note` names the scenarios on either side, λ₁
  // growing).
  struct WatchedCondition {
    CodimensionTwoType type;
    double (*function)(const MonodromyMatrix&);
    const char* note;
  };
  static constexpr std::array<WatchedCondition, 4> watched_on_grazing_ = {
      WatchedCondition{CodimensionTwoType::grazing_period_doubling, det_plus_identity, ""},
      WatchedCondition{CodimensionTwoType::grazing_fold, det_minus_identity, ""},
      WatchedCondition{CodimensionTwoType::grazing_scenario_change,
                       dominant_multiplier_past_quarter,
                       "lambda1 = 1/4: period_adding below, period_adding_with_chaos above"},
      WatchedCondition{CodimensionTwoType::grazing_scenario_change,
                       dominant_multiplier_past_two_thirds,
                       "lambda1 = 2/3: period_adding_with_chaos below, chaos above"}};
  // Along a Neimark–Sacker curve: the pair on the unit circle meeting at +1
  // or −1 (det(M ∓ I) through zero; with N > 2 reported only where two
  // multipliers are there, pair_at, not where a third, real one crosses).
  static constexpr std::array<WatchedCondition, 2> watched_on_neimark_sacker_ = {
      WatchedCondition{CodimensionTwoType::resonance_1_1, det_minus_identity, ""},
      WatchedCondition{CodimensionTwoType::resonance_1_2, det_plus_identity, ""}};

  // The conditions watched along this curve (none but on grazing and
  // Neimark–Sacker curves).
  std::span<const WatchedCondition> watched_conditions() const {
    if (grazing_) return watched_on_grazing_;
    if (request_.type == CurveType::neimark_sacker) return watched_on_neimark_sacker_;
    return {};
  }

  // Each watched condition whose sign differs between the curve point a and
  // the new point b (reached from a by the arclength `step` along `tangent`),
  // located on the curve.
  void detect_codimension_two(const Vector& a, const Vector& tangent, double step,
                              const Corrected& b) {
    const auto watched = watched_conditions();
    for (std::size_t k = 0; k < watched.size(); ++k) {
      const double fa = last_tests_[k], fb = watched[k].function(b.at.orbit.monodromy);
      if (!(fa * fb < 0.0)) continue;
      const auto value = [&](const Corrected& c) {
        return watched[k].function(c.at.orbit.monodromy);
      };
      const auto keep = [&](const Corrected& c) { return keeps(watched[k].type, c); };
      if (auto point = locate(watched[k].type, watched[k].note, value, keep, a, tangent, step, fa))
        result_.points.push_back(std::move(*point));
    }
  }

  // A cusp between the fold curve's point a and the new point (reached from
  // a by the arclength `step` along `tangent`, where the curve's tangent is
  // `next`): the tangent's parameter part reverses. On a fold curve that part
  // is σ·(w·∂F/∂p₂, −w·∂F/∂p₁), w the left null vector of M − I, so it
  // vanishes only where σ, the fold's quadratic coefficient, does (the curve
  // in (x, p₁, p₂) runs on through it, along the null vector). The test
  // function is the parameter part's projection on a's, located as the
  // watched conditions are; reported where the parameter part is zero there
  // (tangent_along_state).
  void detect_cusp(const Vector& a, const Vector& tangent, double step, const Vector& next) {
    const auto parameter_part = [&](const Vector& t) {
      return Eigen::Vector2d(t[p1_], t[p2_]);
    };
    const Eigen::Vector2d reference = parameter_part(tangent);
    const double fa = reference.squaredNorm();
    if (!(parameter_part(next).dot(reference) < 0.0)) return;
    const auto value = [&](const Corrected& c) {
      const auto t = tangent_of(c.jacobian, tangent);
      if (!t) throw std::runtime_error("no curve tangent");
      return parameter_part(*t).dot(reference);
    };
    const auto keep = [&](const Corrected& c) { return tangent_along_state(c, tangent); };
    if (auto point = locate(CodimensionTwoType::cusp, "", value, keep, a, tangent, step, fa))
      result_.points.push_back(std::move(*point));
  }

  // The cubic coefficient of the flip's normal form at the period-doubling
  // curve's point c (η ↦ −η + κη³ on the centre manifold; Kuznetsov,
  // "Elements of applied bifurcation theory", the flip of maps):
  //   κ = ⟨p, C(q,q,q)⟩/6 + ⟨p, B(q, (I − M)⁻¹ B(q,q))⟩/2,
  // q and p the eigenvectors of M and Mᵀ for −1 (⟨p, q⟩ = 1), B and C the
  // map's second and third derivatives, by central differences of the map
  // with the step h = 1e-3 (1 + |x|) along q (and along (I − M)⁻¹B(q,q)).
  // The map's error ε enters as ε/h³: κ is known to about 1e-3 on an
  // integrated map. NaN where a run fails or where a run of the stencil has
  // another impact signature (the map is not smooth across it: near a graze).
  double flip_coefficient(const Corrected& c) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const MonodromyMatrix& m = c.at.orbit.monodromy;
    Matrix a(n_, n_);
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) a(i, j) = m[i][j];
    const Matrix identity = Matrix::Identity(n_, n_);
    Vector q = last_right_singular_vector(a + identity);
    Vector p = last_right_singular_vector((a + identity).transpose());
    if (!q.allFinite() || !p.allFinite() || !(q.norm() > 0.0)) return nan;
    q.normalize();
    if (!(std::fabs(p.dot(q)) > 1e-12)) return nan;
    p /= p.dot(q);
    const Vector x = c.z.head(n_);
    const ContinuationProblem at = problem_.at(p2_of(c.z));
    bool completed = true;
    const auto image = [&](const Vector& y) {
      ++result_.map_evaluations;
      const OrbitEvaluation e =
          at.evaluate(OrbitPoint(y.data(), y.data() + n_), p1_of(c.z), phase_, false, window());
      if (!e.completed || e.signature != c.at.orbit.signature) {
        completed = false;  // a run failed, or the stencil reaches across a graze
        return Vector(Vector::Zero(n_));
      }
      return Vector(Eigen::Map<const Vector>(e.image.data(), n_));
    };
    const double h = 1e-3 * (1.0 + x.norm());
    const Vector centre = Eigen::Map<const Vector>(c.at.orbit.image.data(), n_);
    const Vector up = image(x + h * q), down = image(x - h * q);
    const Vector up2 = image(x + 2.0 * h * q), down2 = image(x - 2.0 * h * q);
    const Vector second = (up - 2.0 * centre + down) / (h * h);
    const Vector third = (up2 - 2.0 * up + 2.0 * down - down2) / (2.0 * h * h * h);
    const Vector v = full_pivot_lu_solve(identity - a, second);
    double mixed = 0.0;
    if (v.norm() > 0.0) {
      const Vector w = v / v.norm();
      const Vector b = (image(x + h * q + h * w) - image(x + h * q - h * w) -
                        image(x - h * q + h * w) + image(x - h * q - h * w)) /
                       (4.0 * h * h);
      mixed = p.dot(b) * v.norm();
    }
    if (!completed) return nan;
    return p.dot(third) / 6.0 + mixed / 2.0;
  }

  // A degenerate period doubling between the curve's point a and the new
  // point (reached from a by the arclength `step` along `tangent`): the
  // flip's cubic coefficient changes sign (from `last_flip_coefficient_` to
  // `next`), located as the watched conditions are.
  void detect_degenerate_flip(const Vector& a, const Vector& tangent, double step, double next) {
    const double fa = last_flip_coefficient_;
    if (!(fa * next < 0.0)) return;
    const auto value = [&](const Corrected& c) {
      const double kappa = flip_coefficient(c);
      if (!std::isfinite(kappa)) throw std::runtime_error("no flip coefficient");
      return kappa;
    };
    const auto keep = [](const Corrected&) { return true; };
    if (auto point = locate(CodimensionTwoType::degenerate_period_doubling, "", value, keep, a,
                            tangent, step, fa))
      result_.points.push_back(std::move(*point));
  }

  // The root of a test function `value` of the corrected curve point on the
  // arclength from a (TOMS 748), each trial point corrected onto the curve;
  // none where `keep` rejects the corrected point at the root.
  template <class TestFunction, class Keep>
  std::optional<CodimensionTwoPoint> locate(CodimensionTwoType type, const std::string& note,
                                            const TestFunction& value, const Keep& keep,
                                            const Vector& a, const Vector& tangent, double step,
                                            double fa) {
    CodimensionTwoPoint point;
    point.type = type;
    point.note = note;
    std::optional<Corrected> last;
    auto on_curve = [&](double s) -> double {
      const Vector predicted = a + s * tangent;
      Corrected c = correct(predicted, tangent, predicted);
      if (!c.converged) throw std::runtime_error("corrector failed");
      const double f = value(c);
      last = std::move(c);
      return f;
    };
    // the parameters' change per unit of arclength, in their own units
    const double rate = std::max(std::fabs(tangent[p1_]) * scale1_, std::fabs(tangent[p2_]) * scale2_);
    try {
      // the end of the bracket on this parametrisation of the curve (the
      // accepted point may have been corrected onto the range's end instead)
      const double fb = on_curve(step);
      if (!(fa * fb < 0.0)) throw std::runtime_error("no sign change on the chord");
      std::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(
          on_curve, 0.0, step, fa, fb, boost::math::tools::eps_tolerance<double>(42), iterations);
      on_curve(0.5 * (bracket.first + bracket.second));
      if (!keep(*last)) return std::nullopt;
      const CurvePoint at = point_of(*last);
      point.p1 = at.p1;
      point.p2 = at.p2;
      point.state = at.state;
      point.multipliers = at.multipliers;
      point.graze_time = at.graze_time;
      point.graze_witness = request_.graze_witness;
      point.error_estimate = rate * (bracket.second - bracket.first);
      point.located = true;
    } catch (const std::exception&) {
      const Vector middle = a + 0.5 * step * tangent;
      point.p1 = p1_of(middle);
      point.p2 = p2_of(middle);
      point.state = state_of(middle);
      point.error_estimate = rate * step;
      point.note += std::string(point.note.empty() ? "" : "; ") +
                    "detected; the corrector failed while locating it";
    }
    return point;
  }

  // Whether the curve's unit tangent at c (oriented along `along`) has a
  // parameter part below 1e-4: a cusp, not a sharp turn of the curve in the
  // parameter plane that the projection test also sees.
  bool tangent_along_state(const Corrected& c, const Vector& along) const {
    const auto t = tangent_of(c.jacobian, along);
    return t && std::hypot((*t)[p1_], (*t)[p2_]) <= 1e-4;
  }

  // Whether two multipliers of m lie at `target` (within 1e-4: a double
  // multiplier is known only to the square root of the map's error).
  static bool pair_at(const MonodromyMatrix& m, double target) {
    int near = 0;
    for (const std::complex<double>& lambda : multipliers_of(m))
      if (std::abs(lambda - target) <= 1e-4) ++near;
    return near >= 2;
  }

  // Whether a located point of `type` at c is one: a threshold of λ₁ where
  // the eigenvalue rule applies (rule_applies), a resonance where two
  // multipliers are at ±1 (pair_at); every other type as located.
  bool keeps(CodimensionTwoType type, const Corrected& c) const {
    switch (type) {
      case CodimensionTwoType::grazing_scenario_change: return rule_applies(c.z);
      case CodimensionTwoType::resonance_1_1: return pair_at(c.at.orbit.monodromy, 1.0);
      case CodimensionTwoType::resonance_1_2: return pair_at(c.at.orbit.monodromy, -1.0);
      default: return true;
    }
  }

  // The linear part of the grazing orbit's normal form at the grazing curve's
  // point z (linear_normal_form, from the orbit's local flow at its graze);
  // none where the problem gives no local flow.
  std::optional<GrazingNormalForm> normal_form_at(const Vector& z) const {
    const ContinuationProblem at = problem_.at(p2_of(z));
    if (!at.grazing_flow) return std::nullopt;
    const double graze = z[tg_] * time_scale_;
    return linear_normal_form(
        at.grazing_flow(state_of(z), p1_of(z), phase_,
                        ContactWindow{request_.graze_witness, graze - window_half_width_,
                                      graze + window_half_width_},
                        graze),
        p1_of(z));
  }

  // Whether the eigenvalue rule decides the scenario at a located threshold
  // of λ₁: its normal form there has every kick gap e_k ≥ 0, λ₁ > 0 and
  // K > 0, so that the rule is period adding, with or without chaos, or
  // chaos, not a jump. Where the normal form cannot be formed the threshold
  // is reported as it is.
  bool rule_applies(const Vector& z) const {
    const auto form = normal_form_at(z);
    if (!form || !form->available) return true;
    return form->rule != GrazingScenario::jump && form->rule != GrazingScenario::not_applicable;
  }

  // The signs of an impact's kick on the later gaps, which the eigenvalue
  // rule reads beside λ₁: the least of K = C P₁ E (the dominant mode's share)
  // and of e_k = C Nᵏ⁻¹ E (k = 1 … 24), over the largest |e_k|. Positive
  // where none drives a later iterate into the wall; through zero the rule
  // changes between jump and a local attractor (a degenerate normal form).
  // NaN where the form is unavailable or K is not formed (λ₁ complex).
  static double kick_margin(const GrazingNormalForm& form) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!form.available || form.kick_gaps.empty() || !std::isfinite(form.dominant_product))
      return nan;
    double largest = 0.0, least = INFINITY;
    for (double e : form.kick_gaps) {
      largest = std::max(largest, std::fabs(e));
      least = std::min(least, e);
    }
    if (!(largest > 0.0)) return nan;
    return std::min(least, form.dominant_product) / largest;
  }

  // Which of the kick's signs is the least (kick_margin): "K" or "e_k" with
  // its k.
  static std::string least_kick_term(const GrazingNormalForm& form) {
    const auto least = std::min_element(form.kick_gaps.begin(), form.kick_gaps.end());
    if (least == form.kick_gaps.end() || form.dominant_product <= *least) return "K";
    return "e_" + std::to_string(1 + (least - form.kick_gaps.begin()));
  }

  // A degenerate normal form between the grazing curve's point a and the new
  // point (reached from a by the arclength `step` along `tangent`, where the
  // normal form is `next`): the kick margin changes sign and the rule with
  // it, located as the watched conditions are; the note names the term at
  // zero and the rule on either side.
  void detect_kick_sign_change(const Vector& a, const Vector& tangent, double step,
                               const std::optional<GrazingNormalForm>& next) {
    if (!last_form_ || !next) return;
    const double fa = kick_margin(*last_form_), fb = kick_margin(*next);
    if (!(fa * fb < 0.0) || last_form_->rule == next->rule) return;
    const GrazingNormalForm& positive = fa > 0.0 ? *last_form_ : *next;
    const GrazingNormalForm& negative = fa > 0.0 ? *next : *last_form_;
    const std::string term = least_kick_term(negative);
    const std::string note = term + " = 0: " + std::string(to_string(positive.rule)) +
                             " where " + term + " > 0, " + std::string(to_string(negative.rule)) +
                             " where " + term + " < 0";
    const auto value = [&](const Corrected& c) {
      const auto form = normal_form_at(c.z);
      const double margin = form ? kick_margin(*form) : std::numeric_limits<double>::quiet_NaN();
      if (!std::isfinite(margin)) throw std::runtime_error("no normal form");
      return margin;
    };
    const auto keep = [](const Corrected&) { return true; };
    if (auto point = locate(CodimensionTwoType::grazing_scenario_change, note, value, keep, a,
                            tangent, step, fa))
      result_.points.push_back(std::move(*point));
  }

  // The fraction of the span between the section (moved by `shift_time`) and
  // the nearest event (the graze counted as one).
  double clearance(const OrbitEvaluation& orbit, double shift_time, double graze_time) const {
    double nearest = 0.5;
    auto include = [&](double t) {
      double u = std::fmod(t - shift_time, orbit.span);
      if (u < 0.0) u += orbit.span;
      nearest = std::min({nearest, u / orbit.span, 1.0 - u / orbit.span});
    };
    for (double t : orbit.event_times) include(t);
    if (grazing_) include(graze_time);
    return nearest;
  }

  // The stroboscopic map jumps where an event crosses the section: the curve
  // is computed on the section phase, among 16, farthest from every event of
  // the start's orbit (the requested one where it is clear by 2 % of the
  // span); states are reported on the requested section.
  void choose_section(Vector& z) {
    const OrbitEvaluation orbit =
        at_start_.evaluate(state_of(z), p1_of(z), phase_, false, window());
    if (!orbit.completed || orbit.span <= 0.0) return;
    const double graze = grazing_ ? z[tg_] * time_scale_ : 0.0;
    if (clearance(orbit, 0.0, graze) > 0.02) return;
    double best_shift = 0.0, best = clearance(orbit, 0.0, graze);
    for (int j = 1; j < 16; ++j) {
      const double shift = 2.0 * std::numbers::pi * j / 16.0;
      const double value = clearance(orbit, shift / orbit.omega, graze);
      if (value > best) {
        best = value;
        best_shift = shift;
      }
    }
    if (best_shift == 0.0) return;
    const double phase = std::remainder(requested_phase_ + best_shift, 2.0 * std::numbers::pi);
    const auto moved = at_start_.transport(state_of(z), p1_of(z), phase_, phase);
    if (!moved) return;
    phase_ = phase;
    for (int i = 0; i < n_; ++i) z[i] = (*moved)[i];
    if (grazing_) {
      double t = std::fmod(z[tg_] * time_scale_ - best_shift / orbit.omega, orbit.span);
      if (t < 0.0) t += orbit.span;
      z[tg_] = t / time_scale_;
      window_center_ = t;
    }
  }

  // The curve ends where it meets a graze: past it the orbit it follows
  // penetrates the wall.
  CurveResult stop_at(CodimensionTwoPoint graze) {
    const std::string detail = "grazing: " + graze.note;
    result_.points.push_back(std::move(graze));
    return stop(StopReason::signature_change, detail);
  }

  // The step fell below the smallest: where the last orbit grazes within
  // reach (the square-root singularity stops the corrector), there;
  // otherwise the corrector cannot pass this point.
  CurveResult stop_below_smallest_step(double h) {
    if (stops_at_grazes())
      if (auto graze = meets_graze(h)) return stop_at(std::move(*graze));
    return stop(StopReason::branch_point,
                "step below the smallest: the corrector cannot pass this point");
  }

  CurveResult stop(StopReason reason, const std::string& detail) {
    result_.stop_reason = reason;
    result_.stop_detail = detail;
    return finish();
  }
  CurveResult finish() { return std::move(result_); }

  const TwoParameterProblem& problem_;
  const CurveRequest& request_;
  ContinuationProblem at_start_;
  bool grazing_ = false;
  bool contact_ = false;                  // a contact onset or end: the landing push's zero
  bool boundary_ = false;                 // a scene's parameter boundary: its zero
  bool chatter_ = false;                  // a chatter onset: its margin's zero
  int n_ = 2;                             // N: the state's components on the section
  int p1_ = 2, p2_ = 3, tg_ = 4;          // the indices of p₁, p₂ and t_g in z
  int size_ = 4;                          // unknowns: (x, p₁, p₂ [, t_g])
  double scale1_ = 1.0, scale2_ = 1.0;    // the parameters' units of arclength (their ranges)
  double time_scale_ = 1.0;               // t_g's unit of arclength: nT at the start (s)
  double window_center_ = 0.0;            // s since the working section
  double window_half_width_ = 0.0;        // s: contacts suppressed within this of the graze
  double h_initial_ = 0.01, h_min_ = 1e-7, h_max_ = 0.02;
  double requested_phase_ = 0.0, phase_ = 0.0;  // rad: the requested and the working section
  Vector z_, tangent_;
  std::string last_signature_;            // the last point's orbit's impact signature
  double last_flip_coefficient_ = 0.0;    // a period-doubling curve: κ at the last point
  std::array<double, watched_on_grazing_.size()> last_tests_{};  // the watched conditions at the
                                                                // last point
  std::optional<GrazingNormalForm> last_form_;  // a grazing curve: the last point's normal form
  CurveResult result_;
};

}  // namespace

CurveResult continue_curve(const TwoParameterProblem& problem, const CurveRequest& request) {
  return CurveDriver(problem, request).run();
}

}  // namespace impactlab
