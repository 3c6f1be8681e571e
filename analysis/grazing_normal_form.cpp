#include <impactlab/analysis/grazing_normal_form.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

#include <Eigen/Core>

#include <impactlab/analysis/dense_solve.hpp>
#include <impactlab/analysis/eigen_vector_conversions.hpp>

namespace impactlab {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

MatrixXd matrix(const MonodromyMatrix& m) {
  const auto n = static_cast<Eigen::Index>(m.size());
  MatrixXd a(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) a(i, j) = m[i][j];
  return a;
}

MonodromyMatrix rows_of(const MatrixXd& a) {
  MonodromyMatrix m(a.rows(), std::vector<double>(a.cols()));
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j) m[i][j] = a(i, j);
  return m;
}

// x with A x = b (full pivoting; non-finite where A is singular)
VectorXd solve(const MatrixXd& a, const VectorXd& b) { return full_pivot_lu_solve(a, b); }

// The normal form's pieces as Eigen objects, once per call.
struct Pieces {
  MatrixXd n;
  VectorXd m, c, e;
  double d = 0.0, a = 0.0;
  explicit Pieces(const GrazingNormalForm& form)
      : n(matrix(form.linear)),
        m(to_eigen(form.parameter_vector)),
        c(to_eigen(form.gap_gradient)),
        e(to_eigen(form.root_vector)),
        d(form.gap_parameter),
        a(form.map.gap_acceleration) {}
  [[nodiscard]] Eigen::Index size() const { return n.rows(); }
  [[nodiscard]] VectorXd virtual_fixed_point(double mu) const {
    return solve(MatrixXd::Identity(size(), size()) - n, m * mu);
  }
};

}  // namespace

GrazingScenario eigenvalue_rule(const GrazingNormalForm& form) {
  if (!form.available || form.eigenvalues.empty()) return GrazingScenario::not_applicable;
  for (const auto& lambda : form.eigenvalues)
    if (std::fabs(lambda.imag()) > 1e-12 * (1.0 + std::abs(lambda)))
      return GrazingScenario::not_applicable;
  const double lambda1 = form.eigenvalues.front().real();
  if (!(std::fabs(lambda1) < 1.0)) return GrazingScenario::not_applicable;
  double largest = 0.0;
  for (double e : form.kick_gaps) largest = std::max(largest, std::fabs(e));
  for (double e : form.kick_gaps)
    if (e < -1e-12 * largest) return GrazingScenario::jump;
  if (!(lambda1 > 0.0) || !(form.dominant_product > 0.0)) return GrazingScenario::jump;
  if (lambda1 < 0.25) return GrazingScenario::period_adding;
  if (lambda1 < 2.0 / 3.0) return GrazingScenario::period_adding_with_chaos;
  return GrazingScenario::chaos;
}

MaximalOrbit maximal_orbit(const GrazingNormalForm& form, int n, double mu) {
  MaximalOrbit orbit;
  orbit.n = n;
  if (!form.available || n < 1 || !form.further_touches.empty()) return orbit;
  const Pieces p(form);
  const Eigen::Index size = p.size();
  const MatrixXd identity = MatrixXd::Identity(size, size);
  MatrixXd power = identity;  // Nⁿ⁻¹
  for (int k = 1; k < n; ++k) power = p.n * power;
  const VectorXd kick = solve(identity - p.n * power, power * p.e);  // (I − Nⁿ)⁻¹ Nⁿ⁻¹ E
  const double cn = p.c.dot(kick);
  const double g = form.gap_per_parameter * mu;
  const double discriminant = cn * cn - 4.0 * g;
  if (!(discriminant >= 0.0) || !std::isfinite(cn)) return orbit;
  // the root of s² + c_n s + g = 0 that vanishes with g
  const double s =
      g == 0.0 ? 0.0 : -2.0 * g / (cn + std::copysign(std::sqrt(discriminant), cn));
  if (!(s > 0.0)) return orbit;
  orbit.exists = true;
  orbit.root = s;
  orbit.impact_speed = std::sqrt(2.0 * p.a) * s;
  const VectorXd start = p.virtual_fixed_point(mu) + kick * s;
  orbit.state = to_values(start);
  // the n − 1 iterations after the impact stay clear of the wall
  VectorXd x = p.n * start + p.m * mu + p.e * s;
  orbit.admissible = true;
  for (int k = 1; k < n; ++k) {
    if (p.c.dot(x) + p.d * mu < 0.0) orbit.admissible = false;
    x = p.n * x + p.m * mu;
  }
  const MatrixXd jacobian = power * (p.n - p.e * p.c.transpose() / (2.0 * s));
  orbit.multipliers = multipliers_of(rows_of(jacobian));
  orbit.stable = std::all_of(orbit.multipliers.begin(), orbit.multipliers.end(),
                             [](const std::complex<double>& m) { return std::abs(m) < 1.0; });
  return orbit;
}

namespace {

// The normal form iterated, on vectors and matrices of type Vec and Mat:
// fixed-capacity ones for the small dimensions (no allocation per
// iteration), dynamic ones beyond.
template <class Vec, class Mat>
class Iteration {
 public:
  explicit Iteration(const GrazingNormalForm& form) {
    const auto n = static_cast<Eigen::Index>(form.linear.size());
    const auto mat = [&](const MonodromyMatrix& m) {
      Mat a = Mat::Zero(n, n);
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j) a(i, j) = m[i][j];
      return a;
    };
    const auto vec = [&](const std::vector<double>& v) {
      Vec a = Vec::Zero(n);
      for (Eigen::Index i = 0; i < n; ++i) a(i) = v[i];
      return a;
    };
    n_ = mat(form.linear);
    m_ = vec(form.parameter_vector);
    // the first touch's own L only where the map is a composition (else E = N L)
    touches_.push_back({vec(form.gap_gradient),
                        form.further_touches.empty() ? Vec(Vec::Zero(n)) : vec(form.map.leading),
                        form.gap_parameter});
    e_ = vec(form.root_vector);
    for (const FurtherTouch& touch : form.further_touches)
      touches_.push_back(
          {vec(touch.map.gap_gradient), vec(touch.map.leading), touch.gap_parameter});
    for (std::size_t j = 0; j < form.segment_flows.size(); ++j) {
      flows_.push_back(mat(form.segment_flows[j]));
      shifts_.push_back(vec(form.segment_parameter_vectors[j]));
    }
  }
  [[nodiscard]] double gap(const Vec& x, double mu) const {
    return touches_[0].c.dot(x) + touches_[0].d * mu;
  }
  // one iteration of x (and of the tangent vector); the √(−h) of its impacts
  // into `roots`, the largest |h| of its touches into `largest`
  void step(Vec& x, Vec& tangent, double mu, std::vector<double>& roots, double& largest) const {
    if (flows_.empty()) {
      const double h = gap(x, mu);
      largest = std::max(largest, std::fabs(h));
      Vec image = n_ * x + m_ * mu;
      Vec next = n_ * tangent;
      if (h < 0.0) {
        const double s = std::sqrt(-h);
        image += e_ * s;
        next -= e_ * (touches_[0].c.dot(tangent) / (2.0 * s));
        roots.push_back(s);
      }
      x = image;
      tangent = next;
      return;
    }
    for (std::size_t j = 0; j < touches_.size(); ++j) {
      const Touch& touch = touches_[j];
      const double h = touch.c.dot(x) + touch.d * mu;
      largest = std::max(largest, std::fabs(h));
      if (h < 0.0) {
        const double s = std::sqrt(-h);
        x += touch.leading * s;
        tangent -= touch.leading * (touch.c.dot(tangent) / (2.0 * s));
        roots.push_back(s);
      }
      x = flows_[j] * x + shifts_[j] * mu;
      tangent = flows_[j] * tangent;
    }
  }
  [[nodiscard]] Vec start(double mu) const {
    const auto n = n_.rows();
    Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n) - Eigen::MatrixXd(n_);
    const Eigen::VectorXd b = Eigen::VectorXd(m_) * mu;
    const Eigen::VectorXd x = full_pivot_lu_solve(a, b);
    return Vec(x);
  }

 private:
  struct Touch {
    Vec c, leading;
    double d;
  };
  Mat n_;
  Vec m_, e_;
  std::vector<Touch> touches_;
  std::vector<Mat> flows_;
  std::vector<Vec> shifts_;
};

// The smallest p ≤ 400 with each of the last 2p iterates (of `kept`, a ring
// whose newest is at `newest`) within `tolerance` of the one p before; 0
// where none.
template <class Vec>
int period_of(const std::vector<Vec>& kept, int newest, int count, double tolerance) {
  const int size = static_cast<int>(kept.size());
  const auto at = [&](int back) { return kept[((newest - back) % size + size) % size]; };
  for (int p = 1; p <= 400 && 2 * p < count; ++p) {
    bool repeats = true;
    for (int i = 0; i < 2 * p && repeats; ++i)
      repeats = (at(i) - at(i + p)).template lpNorm<Eigen::Infinity>() <= tolerance;
    if (repeats) return p;
  }
  return 0;
}

// The √(−h) of each iteration's impacts (at most one per touch), kept for the
// last `ring` iterations without an allocation per iteration.
class RootRing {
 public:
  RootRing(int ring, int touches)
      : ring_(ring), width_(touches), roots_(static_cast<std::size_t>(ring * touches)),
        counts_(static_cast<std::size_t>(ring), 0) {}
  void put(int i, const std::vector<double>& roots) {
    const int slot = i % ring_;
    const int count = std::min(static_cast<int>(roots.size()), width_);
    for (int k = 0; k < count; ++k) roots_[slot * width_ + k] = roots[k];
    counts_[slot] = count;
  }
  // the roots of the iteration `back` before i
  template <class F>
  void each(int i, int back, F&& f) const {
    const int slot = ((i - back) % ring_ + ring_) % ring_;
    for (int k = 0; k < counts_[slot]; ++k) f(roots_[slot * width_ + k]);
  }
  [[nodiscard]] int count(int i, int back) const {
    return counts_[((i - back) % ring_ + ring_) % ring_];
  }
  [[nodiscard]] double root(int i, int back, int k) const {
    return roots_[((i - back) % ring_ + ring_) % ring_ * width_ + k];
  }

 private:
  int ring_, width_;
  std::vector<double> roots_;
  std::vector<int> counts_;
};

// Whether the impacts of the last `period` iterations (newest at i) repeat,
// to 1e-2 relative, after half of it.
bool halves_alike(const RootRing& roots, int i, int period) {
  const int half = period / 2;
  for (int back = 0; back < half; ++back) {
    if (roots.count(i, back) != roots.count(i, back + half)) return false;
    for (int k = 0; k < roots.count(i, back); ++k) {
      const double a = roots.root(i, back, k), b = roots.root(i, back + half, k);
      if (std::fabs(a - b) > 1e-2 * std::max(a, b)) return false;
    }
  }
  return true;
}

template <class Vec, class Mat>
NormalFormAttractor iterate(const GrazingNormalForm& form, double mu) {
  NormalFormAttractor attractor;
  attractor.distance = mu;
  const Iteration<Vec, Mat> map(form);
  const double nu = std::fabs(form.gap_per_parameter * mu);
  double kick = 0.0;
  for (double e : form.kick_gaps) kick = std::max(kick, std::fabs(e));
  // a local attractor keeps its gaps within a few times κ√ν + ν (an impact of
  // speed ∝ √ν kicks later gaps by at most κ√ν); beyond 30 times that, the
  // motion has left the graze's neighbourhood
  const double scale = kick * std::sqrt(nu) + nu;
  const double bound = 30.0 * scale;
  const double root_scale = std::sqrt(2.0 * form.map.gap_acceleration);
  const auto n = static_cast<Eigen::Index>(form.linear.size());
  Vec x = map.start(mu);
  Vec tangent = Vec::Constant(n, 1.0 / std::sqrt(static_cast<double>(n)));
  // up to 4000 iterations; the last 1000 kept (a ring), the period looked for
  // every 50 from the 250th, every 250 from the 1000th; the Lyapunov exponent
  // from the 300th
  constexpr int most = 4000, ring = 1000, lyapunov_from = 300;
  std::vector<Vec> kept(ring, Vec::Zero(n));
  RootRing roots_of(ring, 1 + static_cast<int>(form.further_touches.size()));
  std::vector<double> roots, speeds;
  double log_growth = 0.0;
  int measured = 0, period = 0, i = 0;
  for (; i < most; ++i) {
    roots.clear();
    double largest = 0.0;
    map.step(x, tangent, mu, roots, largest);
    if (!std::isfinite(largest) || largest > bound) {
      attractor.kind = "escapes";
      return attractor;
    }
    const double norm = tangent.norm();
    if (norm > 0.0 && std::isfinite(norm)) {
      tangent /= norm;
      if (i >= lyapunov_from) {
        log_growth += std::log(norm);
        ++measured;
      }
    }
    kept[i % ring] = x;
    roots_of.put(i, roots);
    if (i >= 250 && i % (i < 1000 ? 50 : 250) == 0) {
      period = period_of(kept, i % ring, std::min(i + 1, ring), 1e-7 * scale);
      // an even period whose two halves impact alike may be the slow approach
      // to the half period's orbit near its period doubling (a multiplier
      // near −1): iterated on to the end before it is believed
      if (period > 0 && !(period % 2 == 0 && halves_alike(roots_of, i, period))) break;
      period = 0;
      // no period yet and a clearly positive Lyapunov exponent over 1200
      // iterations: chaotic (a slow approach to a periodic orbit has one ≤ 0)
      if (i >= 1500 && log_growth / measured > 0.02) break;
    }
  }
  if (period == 0 && i == most) {
    --i;
    period = period_of(kept, i % ring, ring, 1e-7 * scale);
  }
  if (period == 0) {
    // the impact speeds of the last 1000 iterations (the ring)
    speeds.clear();
    for (int back = 0; back < std::min(i + 1, ring); ++back)
      roots_of.each(i, back, [&](double root) { speeds.push_back(root_scale * root); });
  }
  attractor.lyapunov = measured > 0 ? log_growth / measured : 0.0;
  if (period > 0) {
    attractor.kind = "periodic";
    attractor.period = period;
    // the impacts of the last period
    for (int back = period - 1; back >= 0; --back)
      roots_of.each(i, back, [&](double s) { attractor.impact_speeds.push_back(root_scale * s); });
    attractor.impacts = static_cast<int>(attractor.impact_speeds.size());
    for (double v : attractor.impact_speeds)
      attractor.max_impact_speed = std::max(attractor.max_impact_speed, v);
    return attractor;
  }
  for (double v : speeds) attractor.max_impact_speed = std::max(attractor.max_impact_speed, v);
  attractor.kind = attractor.lyapunov > 0.0 ? "chaotic" : "aperiodic";
  attractor.impacts = static_cast<int>(speeds.size());
  const std::size_t stride = std::max<std::size_t>(1, speeds.size() / 64);
  for (std::size_t k = 0; k < speeds.size() && attractor.impact_speeds.size() < 64; k += stride)
    attractor.impact_speeds.push_back(speeds[k]);
  return attractor;
}

}  // namespace

NormalFormAttractor normal_form_attractor(const GrazingNormalForm& form, double mu) {
  if (!form.available) {
    NormalFormAttractor none;
    none.distance = mu;
    return none;
  }
  // fixed sizes for (q, q̇), fixed capacity up to 6 states: no allocation per
  // iteration
  if (form.linear.size() == 2) return iterate<Eigen::Vector2d, Eigen::Matrix2d>(form, mu);
  using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
  using SmallMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
  if (form.linear.size() <= 6) return iterate<SmallVec, SmallMat>(form, mu);
  return iterate<VectorXd, MatrixXd>(form, mu);
}

GrazingNormalForm linear_normal_form(const GrazingLocalFlow& local, double parameter) {
  GrazingNormalForm form;
  form.parameter = parameter;
  const auto fail = [&](const std::string& why) {
    form.available = false;
    form.note = why;
    return form;
  };
  if (!local.completed) return fail(local.failure.empty() ? "no local flow" : local.failure);
  if (local.touches.empty() || local.segments.size() != local.touches.size())
    return fail("the local flow has no touch, or not one segment per touch");
  const auto reduced = [](double phase) {
    const double r = std::fmod(phase, 2.0 * std::numbers::pi);
    return r < 0.0 ? r + 2.0 * std::numbers::pi : r;
  };
  const GrazingTouch& first = local.touches.front();
  form.map = discontinuity_map(first);
  if (!form.map.available) return fail(form.map.failure);
  const std::size_t n = first.state.size();
  for (const GrazingSegment& segment : local.segments)
    if (segment.flow.size() != n || segment.parameter_derivative.size() != n)
      return fail("the local flow's pieces do not match the state's dimension");
  form.state = first.state;
  form.phase = reduced(first.phase);
  for (std::size_t j = 1; j < local.touches.size(); ++j) {
    const GrazingTouch& touch = local.touches[j];
    FurtherTouch further;
    further.phase = reduced(touch.phase);
    further.after = std::fmod(touch.time - first.time + local.period, local.period);
    further.witness = touch.witness;
    further.map = discontinuity_map(touch);
    further.gap_parameter = touch.gap_parameter_derivative;
    if (!further.map.available) return fail("a further touch: " + further.map.failure);
    form.further_touches.push_back(further);
  }

  // the section through the first touch: N = A_K ⋯ A_1, M = Σ_j A_K ⋯ A_{j+1} B_j
  MatrixXd linear = MatrixXd::Identity(n, n);
  VectorXd m = VectorXd::Zero(n);
  for (const GrazingSegment& segment : local.segments) {
    const MatrixXd flow = matrix(segment.flow);
    linear = flow * linear;
    m = flow * m + to_eigen(segment.parameter_derivative);
    if (local.touches.size() > 1) {
      form.segment_flows.push_back(segment.flow);
      form.segment_parameter_vectors.push_back(segment.parameter_derivative);
    }
  }
  const VectorXd e = linear * to_eigen(form.map.leading);
  form.linear = rows_of(linear);
  form.parameter_vector = to_values(m);
  form.gap_gradient = first.gap_gradient;
  form.gap_parameter = first.gap_parameter_derivative;
  form.root_vector = to_values(e);
  if (!linear.allFinite() || !m.allFinite() || !e.allFinite() ||
      !std::isfinite(form.gap_parameter))
    return fail("the virtual orbit's flow or parameter derivatives are not finite");
  form.eigenvalues = multipliers_of(form.linear);
  form.available = true;

  // the virtual fixed point's gap per unit μ, and the side it penetrates on
  const MatrixXd identity = MatrixXd::Identity(n, n);
  const VectorXd c = to_eigen(form.gap_gradient);
  form.gap_per_parameter = c.dot(solve(identity - linear, m)) + form.gap_parameter;
  const double a = form.map.gap_acceleration;
  form.root_coefficient = std::sqrt(2.0 * a * std::fabs(form.gap_per_parameter));
  form.impacting_side = form.gap_per_parameter > 0.0 ? -1 : form.gap_per_parameter < 0.0 ? 1 : 0;

  // an impact's effect on the gaps after it, e_k = C Nᵏ⁻¹ E
  VectorXd power_e = e;
  for (int k = 1; k <= 24; ++k) {
    form.kick_gaps.push_back(c.dot(power_e));
    power_e = linear * power_e;
  }
  // K = C P₁ E for a real dominant eigenvalue: (C v)(wᵀ E)/(wᵀ v)
  const std::complex<double> lambda1 = form.eigenvalues.front();
  if (std::fabs(lambda1.imag()) <= 1e-12 * (1.0 + std::abs(lambda1))) {
    const VectorXd v = to_eigen(eigenvector_for(form.linear, lambda1.real()));
    const VectorXd w = to_eigen(eigenvector_for(rows_of(linear.transpose()), lambda1.real()));
    const double overlap = w.dot(v);
    if (std::fabs(overlap) > 1e-12) form.dominant_product = c.dot(v) * w.dot(e) / overlap;
  }

  // the local period-1 impacting orbit: c₁ = C (I − N)⁻¹ E; it exists where
  // −g_μ μ / c₁ > 0
  const double c1 = c.dot(solve(identity - linear, e));
  if (std::isfinite(c1) && c1 != 0.0 && form.gap_per_parameter != 0.0 &&
      form.further_touches.empty()) {
    form.period_one_slope = std::sqrt(2.0 * a) * std::fabs(form.gap_per_parameter / c1);
    form.period_one_side = c1 > 0.0 ? form.impacting_side : -form.impacting_side;
  }

  form.rule = form.further_touches.empty() ? eigenvalue_rule(form) : GrazingScenario::not_applicable;
  return form;
}

GrazingNormalForm grazing_normal_form(const GrazingLocalFlow& local, double parameter) {
  GrazingNormalForm form = linear_normal_form(local, parameter);
  if (!form.available) return form;
  const bool orbit_stable = std::all_of(form.eigenvalues.begin(), form.eigenvalues.end(),
                                        [](const std::complex<double>& l) { return std::abs(l) < 1.0; });
  form.other_side = orbit_stable ? "non_impacting_orbit" : "unstable_non_impacting_orbit";
  if (form.impacting_side == 0) {
    form.note = "degenerate: the virtual orbit's gap does not change with the parameter (g_mu = 0)";
    form.scenario = GrazingScenario::not_applicable;
    return form;
  }
  if (!orbit_stable) {
    form.note = "the grazing orbit is unstable: no attractor to follow through the graze";
    form.scenario = GrazingScenario::not_applicable;
    return form;
  }

  // the normal form iterated at 25 distances, 4 a decade, ν/κ² from 1e-3 to
  // 1e-9 (ν = |g_μ μ| the virtual orbit's penetration, κ = max |e_k| the
  // scale of an impact's kick on later gaps)
  double kick = 0.0;
  for (double value : form.kick_gaps) kick = std::max(kick, std::fabs(value));
  int escapes = 0, periodic = 0, irregular = 0;
  std::vector<int> periods, impacts;
  for (int j = 0; j <= 24; ++j) {
    const double nu = kick * kick * std::pow(10.0, -3.0 - 0.25 * j);
    const double mu = form.impacting_side * nu / std::fabs(form.gap_per_parameter);
    NormalFormAttractor attractor = normal_form_attractor(form, mu);
    if (attractor.kind == "escapes") {
      ++escapes;
    } else if (attractor.kind == "periodic") {
      ++periodic;
      periods.push_back(attractor.period);
      impacts.push_back(attractor.impacts);
      if (form.period_sequence.empty() || form.period_sequence.back() != attractor.period)
        form.period_sequence.push_back(attractor.period);
    } else {
      ++irregular;
    }
    form.attractors.push_back(std::move(attractor));
  }
  if (escapes > 0)
    form.scenario = GrazingScenario::jump;
  else if (irregular == 0 && std::all_of(periods.begin(), periods.end(),
                                         [&](int q) { return q == periods.front(); }) &&
           std::all_of(impacts.begin(), impacts.end(), [](int k) { return k == 1; }))
    form.scenario = GrazingScenario::stable_impacting_orbit;
  else if (irregular == 0)
    form.scenario = GrazingScenario::period_adding;
  else if (periodic > 0)
    form.scenario = GrazingScenario::period_adding_with_chaos;
  else
    form.scenario = GrazingScenario::chaos;
  return form;
}

}  // namespace impactlab
