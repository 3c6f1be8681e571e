#include <impactlab/analysis/branch_corrector.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include <impactlab/analysis/dense_solve.hpp>
#include <impactlab/analysis/impact_signature.hpp>

namespace impactlab::detail {

namespace {

// the parameter's unit of arclength: its range (1 for an empty one)
double range_scale(const ContinuationRequest& request) {
  const double range = std::fabs(request.to - request.from);
  return range > 0.0 ? range : 1.0;
}

}  // namespace

double state_norm(const double* x, int n) {
  if (n == 2) return std::hypot(x[0], x[1]);
  return Eigen::Map<const Eigen::VectorXd>(x, n).norm();
}

StepControl::StepControl(const ContinuationRequest& request, double scale)
    : initial(request.initial_step > 0.0 ? request.initial_step : scale / 100.0),
      smallest(request.min_step > 0.0 ? request.min_step : scale * 1e-7),
      largest(request.max_step > 0.0 ? request.max_step : scale / 50.0) {
  initial /= scale;
  smallest /= scale;
  largest /= scale;
}

double StepControl::after_success(double h, int iterations) const {
  if (iterations <= 3) return std::min(1.5 * h, largest);
  if (iterations <= 6) return std::min(1.1 * h, largest);
  return h * 0.7;
}

template <int Size>
BranchCorrector<Size>::BranchCorrector(const ContinuationProblem& problem,
                                       const ContinuationRequest& request)
    : problem_(problem),
      request_(request),
      n_(static_cast<int>(problem.dimension)),
      scale_(range_scale(request)),
      phase_(problem.phase) {}

template <int Size>
double BranchCorrector<Size>::time_since_requested_section(double t,
                                                           const OrbitEvaluation& orbit) const {
  if (phase_ == problem_.phase || !(orbit.omega > 0.0)) return t;
  double shift = std::remainder(phase_ - problem_.phase, 2.0 * std::numbers::pi);
  if (shift < 0.0) shift += 2.0 * std::numbers::pi;
  return std::fmod(t + shift / orbit.omega, orbit.span);
}

template <int Size>
OrbitPoint BranchCorrector<Size>::reported_state(const Vec& y) const {
  if (phase_ == problem_.phase) return state_of(y);
  const auto moved = problem_.transport(state_of(y), y[n_] * scale_, phase_, problem_.phase);
  return moved ? *moved : state_of(y);
}

template <int Size>
OrbitEvaluation BranchCorrector<Size>::evaluate(const Vec& y, bool detailed,
                                                const ContactWindow& window) {
  ++map_evaluations_;
  return problem_.evaluate(state_of(y), y[n_] * scale_, phase_, detailed, window);
}

template <int Size>
double BranchCorrector<Size>::parameter_step(double p) const {
  return request_.parameter_difference > 0.0 ? request_.parameter_difference
                                             : 1e-6 * (1.0 + std::fabs(p));
}

template <int Size>
std::optional<typename Spaces<Size>::StateVec> BranchCorrector<Size>::parameter_derivative(
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

template <int Size>
void BranchCorrector<Size>::set_jacobian(Correction& c, const typename Spaces<Size>::StateVec& fp,
                                         int n) {
  const MonodromyMatrix& m = c.orbit.monodromy;
  c.jacobian.resize(n, n + 1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) c.jacobian(i, j) = m[i][j] - (i == j ? 1.0 : 0.0);
    c.jacobian(i, n) = fp[i];
  }
  c.has_jacobian = true;
}

template <int Size>
typename BranchCorrector<Size>::Correction BranchCorrector<Size>::correct(
    Vec y, const Vec& tau, const Vec& y_pred, const ContactWindow& window,
    const std::string* signature) {
  Correction c;
  double last_step = INFINITY;
  for (int iteration = 0;; ++iteration) {
    c.orbit = evaluate(y, false, window);
    c.y = y;
    c.iterations = iteration;
    if (!c.orbit.completed) return c;
    if (signature && !same_walls_hit(c.orbit.signature, *signature)) {
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
    Vec step;
    if constexpr (Spaces<Size>::fixed)
      step = system.fullPivLu().solve(right);
    else
      step = full_pivot_lu_solve(system, right);
    if (!step.allFinite()) return c;
    y += step;
    last_step = step.norm();
  }
}

template <int Size>
std::optional<typename BranchCorrector<Size>::Vec> BranchCorrector<Size>::tangent_at(
    Correction& c, const Vec& along) {
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
    t = last_right_singular_vector(c.jacobian);
  }
  if (!(t.norm() > 0.0) || !t.allFinite()) return std::nullopt;
  t.normalize();
  if (t.dot(along) < 0.0) t = -t;
  return t;
}

template class BranchCorrector<3>;
template class BranchCorrector<Eigen::Dynamic>;

}  // namespace impactlab::detail
