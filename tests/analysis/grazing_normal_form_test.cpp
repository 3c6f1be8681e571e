// The discontinuity map and normal form at a located grazing point
// (analysis/grazing_normal_form.hpp) against closed forms derived here,
// independently of the toolkit, for the linear impact oscillator
// ẍ + 2ζẋ + x = A cos ωt, x ≤ σ, ẋ⁺ = −r ẋ⁻, at the grazing of its
// non-impacting period-1 orbit, A/√D = σ (D = (1 − ω²)² + (2ζω)²):
//
// * the orbit x_p = P cos ωt + Q sin ωt (P = A(1 − ω²)/D, Q = 2ζωA/D) touches
//   the stop at its peak, ωt_g = ψ = atan2(Q, P), x_g = (σ, 0);
// * the gap h = σ − x: ∇h = (−1, 0), a = ḧ = σ − A cos ψ, b = h⃛ = Aω sin ψ +
//   2ζ(A cos ψ − σ); the jump per unit of ḣ⁻ = −ẋ⁻ is W = (0, 1 + r);
// * on the section ωt ≡ ψ the virtual map is x ↦ x_p(ψ) + Φ(T)(x − x_p(ψ)),
//   Φ the damped oscillator's transition matrix (underdamped: e^{−ζτ}(cos,
//   sin) of ω_d = √(1 − ζ²); overdamped: e^{Jτ} in cosh and sinh of
//   √(ζ² − 1)), so N = Φ(T), and M = (I − N) ∂x_p(ψ)/∂ω for ω (0 for σ, whose
//   d = ∂h/∂σ = 1);
// * L = −√(2a) W, Q = 2JW − (2b/3a)W, E = N L, g_μ = C(I − N)⁻¹M + d,
//   c = √(2a|g_μ|), c₁ = C(I − N)⁻¹E, the period-1 slope √(2a)|g_μ/c₁|.
//
// The ZDM itself is checked against the exact one (the closed-form flow to the
// impact, the reset, and back), its error falling as |h|^{3/2} with the next
// order and as |h| without; the period-1 impacting orbit's predicted impact
// speed against the toolkit's Newton on the impact map, past the graze; the
// scenario against iterating the normal form and brute-force runs of the full
// system.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <boost/math/tools/roots.hpp>
#include <gtest/gtest.h>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/discontinuity_map.hpp>
#include <impactlab/analysis/grazing_normal_form.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::BifurcationPoint;
using impactlab::BifurcationType;
using impactlab::ContinuationJob;
using impactlab::GrazingNormalForm;
using impactlab::GrazingScenario;
using impactlab::Scene;
using Matrix = std::array<std::array<double, 2>, 2>;
using Vector = std::array<double, 2>;

constexpr double two_pi = 2.0 * std::numbers::pi;

double solve(auto&& f, double a, double b) {
  std::uintmax_t iterations = 300;
  const auto bracket = boost::math::tools::toms748_solve(
      f, a, b, boost::math::tools::eps_tolerance<double>(52), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

Vector times(const Matrix& m, const Vector& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1], m[1][0] * v[0] + m[1][1] * v[1]};
}
// (I − N)⁻¹ v
Vector resolvent(const Matrix& n, const Vector& v) {
  const double a = 1.0 - n[0][0], b = -n[0][1], c = -n[1][0], d = 1.0 - n[1][1];
  const double det = a * d - b * c;
  return {(d * v[0] - b * v[1]) / det, (-c * v[0] + a * v[1]) / det};
}

// The linear impact oscillator and the closed forms of its grazing.
struct Oscillator {
  double zeta = 0.05, A = 1.0, r = 0.8, sigma = 0.2;

  [[nodiscard]] double denominator(double w) const {
    return (1.0 - w * w) * (1.0 - w * w) + 4.0 * zeta * zeta * w * w;
  }
  [[nodiscard]] double amplitude(double w) const { return A / std::sqrt(denominator(w)); }
  // P and Q of the forced response
  [[nodiscard]] Vector response(double w) const {
    return {A * (1.0 - w * w) / denominator(w), 2.0 * zeta * w * A / denominator(w)};
  }
  // the particular solution (x, ẋ) at forcing phase ψ
  [[nodiscard]] Vector particular(double psi, double w) const {
    const auto pq = response(w);
    return {pq[0] * std::cos(psi) + pq[1] * std::sin(psi),
            w * (pq[1] * std::cos(psi) - pq[0] * std::sin(psi))};
  }
  // its derivative in ω at fixed phase (P', Q' in closed form)
  [[nodiscard]] Vector particular_rate(double psi, double w) const {
    const double d = denominator(w);
    const double dd = -4.0 * w * (1.0 - w * w) + 8.0 * zeta * zeta * w;
    const double p = A * (1.0 - w * w) / d, q = 2.0 * zeta * w * A / d;
    const double dp = A * (-2.0 * w * d - (1.0 - w * w) * dd) / (d * d);
    const double dq = 2.0 * zeta * A * (d - w * dd) / (d * d);
    return {dp * std::cos(psi) + dq * std::sin(psi),
            (q * std::cos(psi) - p * std::sin(psi)) + w * (dq * std::cos(psi) - dp * std::sin(psi))};
  }
  [[nodiscard]] double peak_phase(double w) const {
    const auto pq = response(w);
    const double psi = std::atan2(pq[1], pq[0]);
    return psi < 0.0 ? psi + two_pi : psi;
  }
  // the damped oscillator's transition matrix over τ (under- or overdamped)
  [[nodiscard]] Matrix transition(double tau) const {
    const double decay = std::exp(-zeta * tau);
    if (zeta < 1.0) {
      const double wd = std::sqrt(1.0 - zeta * zeta);
      const double c = std::cos(wd * tau), s = std::sin(wd * tau);
      return {{{decay * (c + zeta / wd * s), decay * s / wd},
               {-decay * s / wd, decay * (c - zeta / wd * s)}}};
    }
    const double k = std::sqrt(zeta * zeta - 1.0);
    const double c = std::cosh(k * tau), s = std::sinh(k * tau);
    return {{{decay * (c + zeta / k * s), decay * s / k},
             {-decay * s / k, decay * (c - zeta / k * s)}}};
  }
  // the free flight from (x0, v0) at t0, at t
  [[nodiscard]] Vector flight(double w, double t0, const Vector& x0, double t) const {
    const Vector p0 = particular(w * t0, w), p = particular(w * t, w);
    const Vector u = times(transition(t - t0), Vector{x0[0] - p0[0], x0[1] - p0[1]});
    return {u[0] + p[0], u[1] + p[1]};
  }
  // the ω > 1 where the forced amplitude reaches σ
  [[nodiscard]] double grazing_omega(double from, double to) const {
    return solve([&](double w) { return amplitude(w) - sigma; }, from, to);
  }
};

// The period-1 orbit with one impact per period at ω, in closed form: the
// impact at t with speed V leaves the stop at (σ, −rV) and is back at (σ, V)
// one period later; V from the position condition, t a root of the rate
// condition (TOMS 748), the root nearest the forcing phase `near` whose V is
// positive. {ωt mod 2π, V}, or none.
std::optional<Vector> period_one_impact(const Oscillator& o, double w, double near) {
  const double period = two_pi / w;
  const Matrix m = o.transition(period);
  const auto speed = [&](double t) {
    const Vector p = o.particular(w * t, w);
    return ((m[0][0] - 1.0) * (o.sigma - p[0]) - m[0][1] * p[1]) / (o.r * m[0][1]);
  };
  const auto closing = [&](double t) {
    const Vector p = o.particular(w * t, w);
    const double v = speed(t);
    return m[1][0] * (o.sigma - p[0]) + m[1][1] * (-o.r * v - p[1]) - (v - p[1]);
  };
  std::optional<Vector> best;
  const double centre = near / w;
  const int grid = 4000;
  for (int k = -grid; k < grid; ++k) {
    const double a = centre + 0.2 * k / grid, b = centre + 0.2 * (k + 1) / grid;
    if (!(closing(a) * closing(b) < 0.0)) continue;
    const double t = solve(closing, a, b);
    const double v = speed(t);
    if (!(v > 0.0)) continue;
    const double phase = std::fmod(w * t, two_pi) + (w * t < 0.0 ? two_pi : 0.0);
    if (!best || std::fabs(t - centre) < std::fabs((*best)[0] / w - centre)) best = Vector{phase, v};
  }
  return best;
}

// The normal form's coefficients in closed form at the grazing ω (parameter
// "omega" or "sigma").
struct ClosedForm {
  double omega, psi, a, b, gap_per_parameter, root_coefficient, period_one_slope, d;
  Vector jump, leading, next, m, e;
  Matrix n;
};

ClosedForm closed_form(const Oscillator& o, double w, const std::string& parameter) {
  ClosedForm f{};
  f.omega = w;
  f.psi = o.peak_phase(w);
  f.a = o.sigma - o.A * std::cos(f.psi);
  f.b = o.A * w * std::sin(f.psi) + 2.0 * o.zeta * (o.A * std::cos(f.psi) - o.sigma);
  f.jump = {0.0, 1.0 + o.r};
  const double root = std::sqrt(2.0 * f.a);
  f.leading = {-root * f.jump[0], -root * f.jump[1]};
  const Matrix j = {{{0.0, 1.0}, {-1.0, -2.0 * o.zeta}}};
  const Vector jw = times(j, f.jump);
  const double k = 2.0 * f.b / (3.0 * f.a);
  f.next = {2.0 * jw[0] - k * f.jump[0], 2.0 * jw[1] - k * f.jump[1]};
  f.n = o.transition(two_pi / w);
  if (parameter == "omega") {
    const Vector rate = o.particular_rate(f.psi, w);
    const Vector n_rate = times(f.n, rate);
    f.m = {rate[0] - n_rate[0], rate[1] - n_rate[1]};
    f.d = 0.0;
  } else {
    f.m = {0.0, 0.0};
    f.d = 1.0;
  }
  f.e = times(f.n, f.leading);
  // C = (−1, 0)
  f.gap_per_parameter = -resolvent(f.n, f.m)[0] + f.d;
  f.root_coefficient = std::sqrt(2.0 * f.a * std::fabs(f.gap_per_parameter));
  const double c1 = -resolvent(f.n, f.e)[0];
  f.period_one_slope = root * std::fabs(f.gap_per_parameter / c1);
  return f;
}

Scene linear_impact_scene(const Oscillator& o) {
  Scene scene = impactlab::load_scene("linear_impact");
  scene.values["zeta"] = o.zeta;
  scene.values["r"] = o.r;
  scene.values["sigma"] = o.sigma;
  scene.values["A"] = o.A;
  return scene;
}

std::vector<BifurcationPoint> grazings(const impactlab::ContinuationJobResult& result) {
  std::vector<BifurcationPoint> found;
  for (const auto& branch : result.branches)
    for (const auto& point : branch.result.points)
      if (point.type == BifurcationType::grazing) found.push_back(point);
  return found;
}

// every coefficient of the computed normal form against the closed form
void expect_closed_form(const GrazingNormalForm& form, const ClosedForm& f, double tolerance) {
  ASSERT_TRUE(form.available) << form.note;
  EXPECT_NEAR(std::remainder(form.phase - f.psi, two_pi), 0.0, tolerance);
  EXPECT_NEAR(form.map.gap_acceleration, f.a, tolerance * f.a);
  EXPECT_NEAR(form.map.gap_jerk, f.b, tolerance * (1.0 + std::fabs(f.b)));
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(form.map.jump[i], f.jump[i], tolerance) << i;
    EXPECT_NEAR(form.map.leading[i], f.leading[i], tolerance) << i;
    EXPECT_NEAR(form.map.next[i], f.next[i], tolerance * (1.0 + std::fabs(f.next[i]))) << i;
    EXPECT_NEAR(form.parameter_vector[i], f.m[i], tolerance * (1.0 + std::fabs(f.m[i]))) << i;
    EXPECT_NEAR(form.root_vector[i], f.e[i], tolerance) << i;
    for (int j = 0; j < 2; ++j) EXPECT_NEAR(form.linear[i][j], f.n[i][j], tolerance) << i << j;
  }
  EXPECT_NEAR(form.gap_gradient[0], -1.0, tolerance);
  EXPECT_NEAR(form.gap_gradient[1], 0.0, tolerance);
  EXPECT_NEAR(form.gap_parameter, f.d, tolerance);
  EXPECT_NEAR(form.gap_per_parameter, f.gap_per_parameter,
              tolerance * std::fabs(f.gap_per_parameter));
  EXPECT_NEAR(form.root_coefficient, f.root_coefficient, tolerance * f.root_coefficient);
  EXPECT_NEAR(form.period_one_slope, f.period_one_slope, tolerance * f.period_one_slope);
}

// The continuation of `job` on `scene` and its one grazing point's normal form.
GrazingNormalForm normal_form_of(const Scene& scene, const ContinuationJob& job) {
  const auto points = grazings(impactlab::continue_orbit(scene, job));
  EXPECT_EQ(points.size(), 1u);
  if (points.empty() || !points[0].normal_form) return {};
  return *points[0].normal_form;
}

ContinuationJob omega_job(double from, double to, int impact_wall = 0) {
  ContinuationJob job;
  job.parameter = "omega";
  job.from = from;
  job.to = to;
  job.impact_wall = impact_wall;
  return job;
}

// the non-impacting orbit's state on the section ωt ≡ 0 as the start
ContinuationJob from_free_orbit(const Oscillator& o, ContinuationJob job) {
  const Vector start = o.particular(0.0, job.parameter == "omega" ? job.from : 0.0);
  job.has_start = true;
  job.start = {start[0], start[1]};
  return job;
}

// The overdamped oscillator (ζ = 1.2: real multipliers e^{(−ζ ± √(ζ² − 1))T})
// grazing at ω_g, integrated (no closed-form flow above ζ = 1) by rk8pd at
// rtol 1e-13.
Oscillator overdamped(double omega_graze) {
  Oscillator o;
  o.zeta = 1.2;
  o.sigma = o.amplitude(omega_graze);
  return o;
}
Scene overdamped_scene(const Oscillator& o) {
  Scene scene = linear_impact_scene(o);
  scene.values["integrator.method"] = std::string("taylor");
  scene.values["integrator.rtol"] = 1e-14;
  scene.values["integrator.atol"] = 1e-16;
  return scene;
}

// Both kinds of grazing reach the same point, A/√D = σ, from its two sides:
// on the impact section the period-1 orbit's own impact speed goes to zero as
// ω rises to it; on the stroboscopic section the non-impacting orbit's flight
// maximum reaches the stop as ω falls to it. The two normal forms are the
// closed form's (on the section through the touch, so the same numbers).
TEST(GrazingNormalForm, LinearImpactBothKindsMatchTheClosedForm) {
  const Oscillator o;  // ζ = 0.05, r = 0.8, σ = 0.2, A = 1
  const Scene scene = linear_impact_scene(o);
  const double w = o.grazing_omega(2.3, 2.6);
  const ClosedForm f = closed_form(o, w, "omega");
  const GrazingNormalForm own_impact = normal_form_of(scene, omega_job(2.0, 2.5, 1));
  expect_closed_form(own_impact, f, 1e-8);
  const GrazingNormalForm flight = normal_form_of(scene, from_free_orbit(o, omega_job(2.6, 2.3)));
  expect_closed_form(flight, f, 1e-8);
  // the multipliers e^{(−ζ ± iω_d)T}: complex, so no eigenvalue rule
  EXPECT_GT(std::fabs(own_impact.eigenvalues[0].imag()), 0.1);
  EXPECT_EQ(own_impact.rule, GrazingScenario::not_applicable);
  // the period-1 impacting orbit lives below ω_g (where the orbit penetrates)
  EXPECT_EQ(own_impact.impacting_side, -1);
  EXPECT_EQ(own_impact.period_one_side, -1);
  EXPECT_EQ(flight.impacting_side, -1);
}

// σ as the parameter: the flow does not depend on it (M = 0) and the gap
// does directly (d = 1), so g_μ = 1 and the orbit impacts as σ falls.
TEST(GrazingNormalForm, LinearImpactInSigmaMatchesTheClosedForm) {
  Oscillator o;
  const double w = 2.4;
  o.sigma = o.amplitude(w) * 1.05;
  Scene scene = linear_impact_scene(o);
  scene.values["omega"] = w;
  ContinuationJob job;
  job.parameter = "sigma";
  job.from = o.sigma;
  job.to = o.amplitude(w) * 0.95;
  const Vector start = o.particular(0.0, w);
  job.has_start = true;
  job.start = {start[0], start[1]};
  const GrazingNormalForm form = normal_form_of(scene, job);
  Oscillator at = o;
  at.sigma = o.amplitude(w);
  const ClosedForm f = closed_form(at, w, "sigma");
  expect_closed_form(form, f, 1e-8);
  EXPECT_NEAR(form.gap_per_parameter, 1.0, 1e-8);
  EXPECT_EQ(form.impacting_side, -1);
}

// With real multipliers the rule of Nordmark's square-root map applies and
// agrees with the iterated normal form: λ₁ = 0.185 (ω_g = 2) period adding,
// λ₁ = 0.509 (ω_g = 5) period adding with chaotic windows; the coefficients
// are the closed form's to 1e-8 through the integrated flow too.
TEST(GrazingNormalForm, OverdampedLinearImpactMatchesTheClosedFormAndTheRule) {
  for (const double w : {2.0, 5.0}) {
    const Oscillator o = overdamped(w);
    const GrazingNormalForm form =
        normal_form_of(overdamped_scene(o), from_free_orbit(o, omega_job(1.1 * w, 0.9 * w)));
    expect_closed_form(form, closed_form(o, w, "omega"), 1e-8);
    ASSERT_TRUE(form.available);
    EXPECT_NEAR(form.eigenvalues[0].imag(), 0.0, 1e-12);
    const double lambda1 = std::exp((-o.zeta + std::sqrt(o.zeta * o.zeta - 1.0)) * two_pi / w);
    EXPECT_NEAR(form.eigenvalues[0].real(), lambda1, 1e-8);
    EXPECT_GT(form.dominant_product, 0.0);
    for (double e : form.kick_gaps) EXPECT_GT(e, 0.0);  // (N^k)₁₂ > 0: no kick back into the wall
    const GrazingScenario expected =
        w == 2.0 ? GrazingScenario::period_adding : GrazingScenario::period_adding_with_chaos;
    EXPECT_EQ(form.rule, expected) << w;
    EXPECT_EQ(form.scenario, expected) << w;
    // the periods grow as the distance falls
    ASSERT_GE(form.period_sequence.size(), 3u);
    EXPECT_TRUE(std::is_sorted(form.period_sequence.begin(), form.period_sequence.end()));
  }
}

// The attractor a brute-force run settles on: `periods` forcing periods from
// the state `start` at t0 = 0, its impacts over the last 400 periods. A
// periodic one has every impact `period` forcing periods after the last, at
// one speed (to 1e-3 relative: a near-grazing impact's speed V carries the
// state's error times a/V; the mean of them is the orbit's).
struct SettledAttractor {
  bool periodic = false;
  int period = 0;
  int impacts = 0;
  double speed = 0.0;      // the periodic one's impact speed
  double max_speed = 0.0;  // the largest impact speed seen
};

SettledAttractor settle(Scene scene, double omega, const Vector& start, double periods) {
  scene.values["omega"] = omega;
  scene.values["initial.x"] = start[0];
  scene.values["initial.x_dot"] = start[1];
  impactlab::RunRequest request;
  request.periods = periods;
  const impactlab::RunOutput run = impactlab::simulate(scene, request);
  SettledAttractor found;
  const double period = two_pi / omega, kept_from = run.t_final - 400.0 * period;
  std::vector<double> times, speeds;
  for (const auto& event : run.events)
    if (event.kind == impactlab::EventKind::impact && event.t > kept_from) {
      times.push_back(event.t);
      speeds.push_back(event.qdot_before);
    }
  found.impacts = static_cast<int>(times.size());
  if (times.size() < 3) return found;
  found.max_speed = *std::max_element(speeds.begin(), speeds.end());
  const auto [low, high] = std::minmax_element(speeds.begin(), speeds.end());
  const int first = static_cast<int>(std::lround((times[1] - times[0]) / period));
  bool regular = *high - *low <= 1e-3 * *high;
  for (std::size_t i = 1; i < times.size(); ++i)
    regular = regular && std::lround((times[i] - times[i - 1]) / period) == first;
  found.periodic = regular;
  found.period = regular ? first : 0;
  double mean = 0.0;
  for (double v : speeds) mean += v / static_cast<double>(speeds.size());
  found.speed = regular ? mean : 0.0;
  return found;
}

// The bifurcating orbits past the graze of the overdamped oscillator at
// ω_g = 2 (λ₁ = 0.185: period adding, no chaos): at 1e-4 ... 1e-8 below ω_g
// a run from the virtual orbit settles on an orbit with one impact every n
// periods, n the iterated normal form's, its impact speed the normal form's
// maximal period-n orbit's, V ∝ √|μ|, to a relative error that falls as the
// distance falls (the next order is O(√|μ|) relative).
TEST(GrazingNormalForm, PeriodAddingOrbitsMatchBruteForceRunsPastTheGraze) {
  const double w = 2.0;
  const Oscillator o = overdamped(w);
  const Scene scene = overdamped_scene(o);
  const GrazingNormalForm form =
      normal_form_of(scene, from_free_orbit(o, omega_job(1.1 * w, 0.9 * w)));
  ASSERT_TRUE(form.available);
  double last_error = INFINITY;
  for (int k = 4; k <= 8; ++k) {
    const double mu = form.impacting_side * std::pow(10.0, -k);
    const double omega = form.parameter + mu;
    const SettledAttractor seen = settle(scene, omega, o.particular(0.0, omega), 3000);
    const auto predicted = impactlab::normal_form_attractor(form, mu);
    ASSERT_TRUE(seen.periodic) << k;
    ASSERT_EQ(predicted.kind, "periodic") << k;
    EXPECT_EQ(seen.period, predicted.period) << k;
    const auto orbit = impactlab::maximal_orbit(form, seen.period, mu);
    ASSERT_TRUE(orbit.exists && orbit.admissible && orbit.stable) << k;
    const double error = std::fabs(orbit.impact_speed - seen.speed) / seen.speed;
    EXPECT_LT(error, 10.0 * std::sqrt(std::fabs(mu))) << k;
    EXPECT_LT(error, last_error) << k;
    last_error = error;
  }
}

// The ZDM against the exact one, at a touch where h⃛ ≠ 0: a free flight of
// ẍ + 2ζẋ + x = A cos ωt with a homogeneous part, the stop placed at the
// height of its maximum at t_g. A virtual state y = x_g + δ at t_g with
// h(y) = −η < 0 is flowed (closed form) to its entry into the stop, reset,
// and flowed back to t_g: D(y). The leading order misses D(y) − y by O(η),
// with the next order by O(η^{3/2}).
TEST(DiscontinuityMap, MatchesTheExactMapToItsOrder) {
  const Oscillator o;  // ζ = 0.05, r = 0.8, A = 1
  const double w = 2.4;
  const Vector start = {o.particular(0.0, w)[0] + 0.05, o.particular(0.0, w)[1] + 0.3};
  const auto at = [&](double t) { return o.flight(w, 0.0, start, t); };
  const double tg = solve([&](double t) { return at(t)[1]; }, 0.3, 1.5);  // ẋ = 0, a maximum
  ASSERT_LT(at(tg + 1e-3)[0], at(tg)[0]);
  Oscillator stop = o;
  stop.sigma = at(tg)[0];
  const double xddot = o.A * std::cos(w * tg) - stop.sigma;  // ẋ = 0 there
  const double xdddot = -o.A * w * std::sin(w * tg) - 2.0 * o.zeta * xddot;

  impactlab::GrazingTouch local;
  local.state = {stop.sigma, 0.0};
  local.gap_gradient = {-1.0, 0.0};
  local.rate_gradient = {0.0, -1.0};
  local.field_jacobian = {{0.0, 1.0}, {-1.0, -2.0 * o.zeta}};
  local.reset_jacobian = {{0.0, 0.0}, {0.0, -o.r}};
  local.gap_acceleration = -xddot;
  local.gap_jerk = -xdddot;
  const impactlab::DiscontinuityMap map = impactlab::discontinuity_map(local);
  ASSERT_TRUE(map.available) << map.failure;
  EXPECT_GT(std::fabs(map.gap_jerk), 0.1);
  EXPECT_NEAR(map.jump[1], 1.0 + o.r, 1e-14);

  std::vector<double> leading_errors, next_errors;
  for (const double eta : {1e-4, 1e-5, 1e-6, 1e-7}) {
    const std::vector<double> deviation = {eta, -0.3 * eta};  // h = −η, ḣ = 0.3η
    const Vector y = {stop.sigma + deviation[0], deviation[1]};
    // the entry: the root of σ − x before the virtual trajectory's maximum
    const auto gap = [&](double t) { return stop.sigma - o.flight(w, tg, y, t)[0]; };
    const double peak = solve([&](double t) { return o.flight(w, tg, y, t)[1]; }, tg - 0.1, tg + 0.1);
    const double entry = solve(gap, peak - 0.2, peak);
    const Vector before = o.flight(w, tg, y, entry);
    const Vector exact = o.flight(w, entry, Vector{stop.sigma, -o.r * before[1]}, tg);
    const auto lead = impactlab::discontinuity_jump(map, deviation, false);
    const auto next = impactlab::discontinuity_jump(map, deviation, true);
    double lead_error = 0.0, next_error = 0.0;
    for (int i = 0; i < 2; ++i) {
      const double jump = exact[i] - y[i];
      lead_error = std::max(lead_error, std::fabs(lead[i] - jump));
      next_error = std::max(next_error, std::fabs(next[i] - jump));
    }
    leading_errors.push_back(lead_error / eta);
    next_errors.push_back(next_error / std::pow(eta, 1.5));
  }
  // the errors in their orders: bounded ratios, and the next order's really smaller
  for (std::size_t k = 1; k < leading_errors.size(); ++k) {
    EXPECT_NEAR(leading_errors[k], leading_errors[0], 0.05 * leading_errors[0]) << k;
    EXPECT_LT(next_errors[k], 2.0 * next_errors[0]) << k;
  }
  EXPECT_GT(leading_errors.back(), 0.1);
}

// A leading-order normal form with real multipliers, made by hand: the
// eigenvalue rule and the iterated normal form agree on the classic
// thresholds of the square-root map (λ₁ < 1/4: period adding; < 2/3: with
// chaotic windows; above: chaos), and a kick that drives a later iterate
// into the wall (e₂ < 0: λ₁ < 0) gives a jump.
GrazingNormalForm synthetic(double lambda1, double lambda2) {
  GrazingNormalForm form;
  form.available = true;
  form.map.available = true;
  form.map.gap_acceleration = 0.5;
  form.linear = {{lambda1, 0.0}, {0.0, lambda2}};
  form.eigenvalues = {{lambda1, 0.0}, {lambda2, 0.0}};
  form.gap_gradient = {1.0, 1.0};
  form.gap_parameter = 0.0;
  form.parameter_vector = {-(1.0 - lambda1), -0.5 * (1.0 - lambda2)};  // g_μ = −1.5
  form.root_vector = {1.0, 0.2};
  form.gap_per_parameter = -1.5;
  form.impacting_side = 1;
  for (int k = 1; k <= 24; ++k)
    form.kick_gaps.push_back(std::pow(lambda1, k - 1) + 0.2 * std::pow(lambda2, k - 1));
  form.dominant_product = 1.0;
  return form;
}

TEST(GrazingNormalForm, EigenvalueRuleAgreesWithTheIteratedMap) {
  struct Case {
    double lambda1, lambda2;
    GrazingScenario expected;
  };
  for (const Case& c : {Case{0.15, 0.05, GrazingScenario::period_adding},
                        Case{0.5, 0.1, GrazingScenario::period_adding_with_chaos},
                        Case{0.85, 0.3, GrazingScenario::chaos},
                        Case{-0.6, 0.1, GrazingScenario::jump}}) {
    GrazingNormalForm form = synthetic(c.lambda1, c.lambda2);
    EXPECT_EQ(impactlab::eigenvalue_rule(form), c.expected) << c.lambda1;
    // the iteration at the distances grazing_normal_form uses
    int periodic = 0, irregular = 0, escapes = 0;
    double kick = 0.0;
    for (double e : form.kick_gaps) kick = std::max(kick, std::fabs(e));
    for (int j = 0; j <= 24; ++j) {
      const double mu = kick * kick * std::pow(10.0, -3.0 - 0.25 * j) / 1.5;
      const auto attractor = impactlab::normal_form_attractor(form, mu);
      if (attractor.kind == "escapes") ++escapes;
      else if (attractor.kind == "periodic") ++periodic;
      else ++irregular;
    }
    switch (c.expected) {
      case GrazingScenario::period_adding: EXPECT_EQ(periodic, 25); break;
      case GrazingScenario::period_adding_with_chaos:
        EXPECT_GT(periodic, 0);
        EXPECT_GT(irregular, 0);
        EXPECT_EQ(escapes, 0);
        break;
      case GrazingScenario::chaos: EXPECT_EQ(irregular, 25); break;
      default: EXPECT_GT(escapes, 0); break;
    }
  }
}

// The orbit born at the graze of the section's own impact (the branch the
// impact section follows up to it): its impact speed V₁ ≈ slope·|μ|, with the
// normal form's maximal period-1 orbit against the closed-form orbit at 1e-4
// … 1e-8 below ω_g (past the graze on the impacting side), the relative
// error falling with the distance (it is O(μ)); and the toolkit's own branch
// points nearest the graze (V ≈ 0.005 to 0.01) within the same law.
TEST(GrazingNormalForm, PeriodOneImpactSpeedScalesAsTheNormalFormSays) {
  const Oscillator o;
  const Scene scene = linear_impact_scene(o);
  const auto result = impactlab::continue_orbit(scene, omega_job(2.0, 2.5, 1));
  const auto points = grazings(result);
  ASSERT_EQ(points.size(), 1u);
  const GrazingNormalForm& form = *points[0].normal_form;
  ASSERT_EQ(form.period_one_side, -1);
  double last_error = INFINITY;
  for (int k = 4; k <= 8; ++k) {
    const double mu = -std::pow(10.0, -k);
    const auto exact = period_one_impact(o, form.parameter + mu, form.phase);
    ASSERT_TRUE(exact.has_value()) << k;
    const auto predicted = impactlab::maximal_orbit(form, 1, mu);
    ASSERT_TRUE(predicted.exists && predicted.admissible) << k;
    EXPECT_FALSE(predicted.stable) << k;  // a multiplier ∝ 1/|μ|
    const double error = std::fabs(predicted.impact_speed - (*exact)[1]) / (*exact)[1];
    EXPECT_LT(error, 10.0 * std::fabs(mu)) << k;
    EXPECT_LT(error, 0.3 * last_error) << k;
    last_error = error;
    EXPECT_NEAR(predicted.impact_speed, form.period_one_slope * std::fabs(mu),
                20.0 * std::fabs(mu) * predicted.impact_speed);
  }
  // the branch's last points, computed by Newton on the impact map
  const auto& branch = result.branches.at(0).result.branch;
  for (std::size_t i = branch.size() - 3; i < branch.size(); ++i) {
    const double mu = branch[i].parameter - form.parameter;
    const double v = impactlab::maximal_orbit(form, 1, mu).impact_speed;
    EXPECT_NEAR(v, branch[i].state[1], 30.0 * std::fabs(mu) * v) << mu;
  }
}

// The underdamped oscillator's normal form (multipliers 0.88 e^{±2.57i}) kicks
// the orbit back into the stop two iterations after an impact (e₂ < 0): no
// attractor near the graze, a jump. A brute-force run from the virtual orbit
// just past the graze indeed leaves: the attractor it settles on impacts at
// speeds of order one, far above the first impact's c√|μ|, at every distance.
TEST(GrazingNormalForm, UnderdampedGrazeJumpsAsBruteForceRunsDo) {
  const Oscillator o;
  const Scene scene = linear_impact_scene(o);
  const GrazingNormalForm form = normal_form_of(scene, omega_job(2.0, 2.5, 1));
  ASSERT_TRUE(form.available);
  EXPECT_GT(form.kick_gaps[0], 0.0);
  EXPECT_LT(form.kick_gaps[1], 0.0);
  EXPECT_EQ(form.scenario, GrazingScenario::jump);
  for (const auto& attractor : form.attractors) EXPECT_EQ(attractor.kind, "escapes");
  std::vector<double> speeds;
  for (int k = 4; k <= 7; ++k) {
    const double mu = form.impacting_side * std::pow(10.0, -k);
    const double omega = form.parameter + mu;
    const SettledAttractor seen = settle(scene, omega, o.particular(0.0, omega), 2000);
    ASSERT_GT(seen.impacts, 0) << k;
    EXPECT_GT(seen.max_speed, 30.0 * form.root_coefficient * std::sqrt(std::fabs(mu))) << k;
    speeds.push_back(seen.max_speed);
  }
  // a distant attractor: its impact speeds do not shrink with the distance
  EXPECT_GT(*std::min_element(speeds.begin(), speeds.end()),
            0.5 * *std::max_element(speeds.begin(), speeds.end()));
}

// λ₁ = 0.509 (ω_g = 5): period adding with chaotic windows. Brute-force runs
// from the virtual orbit at the normal form's own distances see what it
// sees: where the normal form settles on an orbit of one impact every n
// periods, so does the run (mostly: window edges move at the next order),
// and both have aperiodic points between the windows.
TEST(GrazingNormalForm, ChaoticWindowsAgreeWithBruteForceRuns) {
  const double w = 5.0;
  const Oscillator o = overdamped(w);
  const Scene scene = overdamped_scene(o);
  const GrazingNormalForm form =
      normal_form_of(scene, from_free_orbit(o, omega_job(1.1 * w, 0.9 * w)));
  ASSERT_EQ(form.scenario, GrazingScenario::period_adding_with_chaos);
  int compared = 0, agreed = 0, seen_irregular = 0;
  for (const auto& predicted : form.attractors) {
    if (std::fabs(predicted.distance) > 1e-3) continue;
    const double omega = form.parameter + predicted.distance;
    const SettledAttractor seen = settle(scene, omega, o.particular(0.0, omega), 3000);
    ++compared;
    if (!seen.periodic) ++seen_irregular;
    const bool same = predicted.kind == "periodic"
                          ? seen.periodic && seen.period == predicted.period
                          : !seen.periodic;
    if (same) ++agreed;
  }
  EXPECT_GE(compared, 15);
  EXPECT_GE(agreed, 0.75 * compared);
  EXPECT_GT(seen_irregular, 0);
}

// jin2003 at ω = 8.5 rad/s: the hanging pendulum doubles its period at V0 =
// 0.6501 m/s into a symmetric oscillation that grows until it grazes both
// walls at once, θ = +θ₀ and −θ₀ half its orbit apart (V0 = 0.652035). The
// normal form has the second touch (the mirror of the first) and predicts a
// jump: an impact drives the next swing deeper into the walls (e₁ < 0).
// Brute-force runs from the grazing orbit's state 1e-4 … 1e-8 m/s past the
// graze settle on an impacting period-2 orbit whose impact speed (0.151
// rad/s, the gap being θ₀ − θ) does not shrink with the distance, while the first impact's c√|μ|
// falls a hundredfold: the motion has left the graze's neighbourhood.
TEST(GrazingNormalForm, Jin2003SymmetricGrazeJumpsAsBruteForceRunsDo) {
  Scene scene = impactlab::load_scene("jin2003");
  scene.values["omega"] = 8.5;
  ContinuationJob job;
  job.parameter = "V0";
  job.from = 0.05;
  job.to = 1.5;
  job.has_start = true;
  job.start = {0.0, 0.0};
  job.doublings = 1;
  const auto points = grazings(impactlab::continue_orbit(scene, job));
  ASSERT_EQ(points.size(), 1u);
  const BifurcationPoint& graze = points[0];
  EXPECT_NEAR(graze.parameter, 0.652034919561, 1e-9);
  ASSERT_TRUE(graze.normal_form && graze.normal_form->available) << graze.normal_form->note;
  const GrazingNormalForm& form = *graze.normal_form;
  ASSERT_EQ(form.further_touches.size(), 1u);
  const auto& mirror = form.further_touches[0];
  EXPECT_NE(mirror.witness, graze.graze_witness);
  EXPECT_NEAR(mirror.after, two_pi / 8.5, 1e-6);  // half the period-2 orbit later
  EXPECT_NEAR(mirror.map.state[0], -form.state[0], 1e-8);
  EXPECT_NEAR(mirror.map.gap_acceleration, form.map.gap_acceleration, 1e-6);
  EXPECT_EQ(form.impacting_side, 1);
  EXPECT_LT(form.kick_gaps[0], 0.0);
  EXPECT_EQ(form.rule, GrazingScenario::not_applicable);  // two touches
  EXPECT_EQ(form.scenario, GrazingScenario::jump);

  const double gap_per_rate = std::fabs(form.gap_gradient[0]);  // the gap θ₀ − θ: 1
  std::vector<double> speeds;
  for (int k = 4; k <= 8; ++k) {
    const double mu = std::pow(10.0, -k);
    Scene past = scene;
    past.values["V0"] = graze.parameter + mu;
    past.values["initial.theta"] = graze.state[0];
    past.values["initial.theta_dot"] = graze.state[1];
    impactlab::RunRequest request;
    request.periods = 800;
    const impactlab::RunOutput run = impactlab::simulate(past, request);
    double fastest = 0.0;
    for (const auto& event : run.events)
      if (event.kind == impactlab::EventKind::impact && event.t > 600.0 * two_pi / 8.5)
        fastest = std::max(fastest, std::fabs(event.qdot_before) * gap_per_rate);
    speeds.push_back(fastest);
    if (k >= 6) { EXPECT_GT(fastest, 5.0 * form.root_coefficient * std::sqrt(mu)) << k; }
  }
  EXPECT_GT(*std::min_element(speeds.begin(), speeds.end()),
            0.9 * *std::max_element(speeds.begin(), speeds.end()));
}

}  // namespace
