// The corrector and the step control of a branch (branch_continuation.hpp):
// the branch's coordinates y = (x, p / range), N + 1 of them, so that the
// parameter's range is one unit of arclength; the section the branch is
// computed on (moved off events, states reported on the requested one);
// Newton on F(y) = Pⁿ(x; p) − x = 0 with the arclength condition
// τ·(y − y_pred) = 0, ∂F/∂x = M − I from the saltation-corrected monodromy
// and ∂F/∂p by a central difference; the branch's unit tangent, the null
// vector of [M − I | F_p]; and the step lengths.
//
// Internal to continuation: the bifurcation locator and the grazing system
// (bifurcation_location.hpp, grazing_system.hpp) correct their trial points
// with the same corrector. Compiled for N = 2 (Size = 3, fixed-size vectors)
// and any N (Eigen::Dynamic) in branch_corrector.cpp.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>

#include <impactlab/analysis/continuation_problem.hpp>

namespace impactlab::detail {

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
double state_norm(const double* x, int n);

// A point on the branch, with what the next step needs.
template <int Size>
struct BranchNode {
  typename Spaces<Size>::Vec y;
  typename Spaces<Size>::Vec tangent;  // unit, pointing along the run
  OrbitEvaluation orbit;               // detailed evaluation at y
  int iterations = 0;
  double step = 0.0;                   // the arclength from the previous node
};

// What Newton's corrector reached from a predicted point.
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

// The step lengths of a branch, in arclength (branch units): the first, the
// smallest (below it the branch stops) and the largest, from the request
// (0: 1/100, 1e-7 and 1/50 of the range); a step grows after an easy
// correction and shrinks after a hard one.
struct StepControl {
  double initial, smallest, largest;

  StepControl(const ContinuationRequest& request, double scale);
  // the step after one corrected in `iterations` Newton iterations
  [[nodiscard]] double after_success(double h, int iterations) const;
};

template <int Size>
class BranchCorrector {
 public:
  using Vec = typename Spaces<Size>::Vec;
  using Correction = NodeCorrection<Size>;

  BranchCorrector(const ContinuationProblem& problem, const ContinuationRequest& request);

  [[nodiscard]] const ContinuationProblem& problem() const { return problem_; }
  [[nodiscard]] const ContinuationRequest& request() const { return request_; }
  [[nodiscard]] int dimension() const { return n_; }  // N
  [[nodiscard]] double scale() const { return scale_; }  // the parameter's unit of arclength

  // --- coordinates ---
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

  // --- the working section (rad): the requested one, or one moved off events ---
  [[nodiscard]] double phase() const { return phase_; }
  void move_section(double phase) { phase_ = phase; }
  // a time since the working section as a time since the requested one (s)
  double time_since_requested_section(double t, const OrbitEvaluation& orbit) const;
  // the state on the requested section
  OrbitPoint reported_state(const Vec& y) const;

  // --- evaluations of the map, counted ---
  OrbitEvaluation evaluate(const Vec& y, bool detailed, const ContactWindow& window);
  void count_evaluation() { ++map_evaluations_; }
  [[nodiscard]] int map_evaluations() const { return map_evaluations_; }

  // Newton on F(y) = 0, τ·(y − y_pred) = 0 from y. A run that does not
  // complete, or (with `signature`) an orbit whose impact signature differs,
  // stops it.
  Correction correct(Vec y, const Vec& tau, const Vec& y_pred, const ContactWindow& window,
                     const std::string* signature);

  // The branch's unit tangent at a corrected point, oriented along `along`.
  // The null vector of the N × (N + 1) Jacobian: for N = 2 the cross product
  // of its rows, otherwise the last right singular vector.
  std::optional<Vec> tangent_at(Correction& c, const Vec& along);

 private:
  double parameter_step(double p) const;
  // ∂F/∂p ≈ (Pⁿ(x; p + h) − Pⁿ(x; p − h)) / 2h (F = Pⁿ − x, x held)
  std::optional<typename Spaces<Size>::StateVec> parameter_derivative(
      const Vec& y, const ContactWindow& window);
  // c.jacobian = [M − I | F_p]
  static void set_jacobian(Correction& c, const typename Spaces<Size>::StateVec& fp, int n);

  const ContinuationProblem& problem_;
  const ContinuationRequest& request_;
  int n_ = 2;              // N: the state's components on the section
  double scale_ = 1.0;     // the parameter's unit of arclength (the range)
  double phase_ = 0.0;     // rad: the section the branch is computed on
  int map_evaluations_ = 0;
};

extern template class BranchCorrector<3>;
extern template class BranchCorrector<Eigen::Dynamic>;

}  // namespace impactlab::detail
