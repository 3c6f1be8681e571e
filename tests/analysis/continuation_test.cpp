// Continuation of periodic orbits (analysis/continuation.hpp) against closed
// forms derived here, independently of the toolkit:
// * the linear impact oscillator's period-1 one-impact orbit: the impact time
//   t* and speed v solve Φ(T) u(t*) = u(t* + T) for the deviation u from the
//   particular solution (Φ the damped oscillator's transition matrix over one
//   forcing period); the monodromy is S Φ with the Newton-impact saltation
//   matrix S = [[−r, 0], [(1 + r)(A cos ωt* − σ)/v, −r]]; period doublings are
//   roots of 1 + tr M + det M, and the grazing point is the ω where the
//   interior maximum of the flight reaches the stop;
// * the bouncing ball's period-1 orbit (flight time T, take-off speed gT/2):
//   with Γ = Aω²/g, cos φ = π(1 − r)/(Γ(1 + r)), and the period doubling at
//   Γ² = (π(1 − r)/(1 + r))² + (2(1 + r²)/(1 + r)²)².
// The located points must agree to 1e-9 relative in the parameter; stable
// branch points agree with the brute-force section (sweep) and `periodic`.
// A Neimark–Sacker point is checked on a synthetic rotating map whose fixed
// point and multipliers are known (no impact oscillator here has one in
// closed form). Two-parameter curves (analysis/curve_continuation.hpp) are checked point by
// point against the same closed forms: the ball's period-doubling amplitude
// as a function of r, the linear oscillator's period doubling in (ω, r), and
// its impact-velocity grazing A/√((1 − ω²)² + (2ζω)²) = σ in (ω, σ).
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <array>
#include <cmath>
#include <complex>
#include <fstream>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <boost/math/tools/roots.hpp>
#include <gtest/gtest.h>

#include <impactlab/analysis/branch_continuation.hpp>
#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/continuation_problem.hpp>
#include <impactlab/analysis/curve_continuation.hpp>
#include <impactlab/analysis/grazing_normal_form.hpp>
#include <impactlab/analysis/impact_signature.hpp>
#include <impactlab/analysis/periodic.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene.hpp>

#include "support/curve_job.hpp"
#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::testing::curve_job;

using impactlab::BifurcationPoint;
using impactlab::BifurcationType;
using impactlab::ContinuationJob;
using impactlab::ContinuationJobResult;
using impactlab::CurveType;
using impactlab::Scene;
using impactlab::StopReason;

constexpr double two_pi = 2.0 * std::numbers::pi;

double solve(auto&& f, double a, double b) {
  std::uintmax_t iterations = 300;
  const auto bracket = boost::math::tools::toms748_solve(
      f, a, b, boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

struct ImpactOscillator {
  double zeta = 0.05, r = 0.8, sigma = 0.0, A = 1.0;
};

// The one-impact period-1 orbit of ẍ + 2ζẋ + x = A cos ωt, x ≤ σ, ẋ⁺ = −r ẋ⁻.
class PeriodOneOrbit {
 public:
  // admissible_only: a flight that reaches beyond the stop is no orbit (set
  // false for the virtual orbit of a grazing point, whose flight touches it)
  PeriodOneOrbit(const ImpactOscillator& o, double omega, bool admissible_only = true)
      : o_(o), omega_(omega) {
    period_ = two_pi / omega;
    wd_ = std::sqrt(1.0 - o.zeta * o.zeta);
    const double denominator =
        (1.0 - omega * omega) * (1.0 - omega * omega) + 4.0 * o.zeta * o.zeta * omega * omega;
    cos_amplitude_ = o.A * (1.0 - omega * omega) / denominator;
    sin_amplitude_ = 2.0 * o.zeta * omega * o.A / denominator;
    transition_ = homogeneous(period_);
    // the impact time: the root of the velocity condition with v > 0 and an
    // admissible flight (x < σ strictly inside)
    const int grid = 3000;
    for (int k = 0; k < grid && !found_; ++k) {
      const double a = period_ * k / grid, b = period_ * (k + 1) / grid;
      if (!(closing(a) * closing(b) < 0.0)) continue;
      const double t = solve([&](double s) { return closing(s); }, a, b);
      const double v = speed(t);
      if (!(v > 0.0)) continue;
      impact_time_ = t;
      speed_ = v;
      found_ = !admissible_only || highest_interior() < o_.sigma;
    }
  }

  [[nodiscard]] bool found() const { return found_; }
  [[nodiscard]] double speed() const { return speed_; }
  [[nodiscard]] double impact_time() const { return impact_time_; }  // in [0, T)

  // (x, ẋ) at time t of the orbit (t in [t*, t* + T])
  [[nodiscard]] std::array<double, 2> state(double t) const {
    const auto phi = homogeneous(t - impact_time_);
    const double u0 = o_.sigma - particular(impact_time_)[0];
    const double du0 = -o_.r * speed_ - particular(impact_time_)[1];
    const auto p = particular(t);
    return {phi[0][0] * u0 + phi[0][1] * du0 + p[0], phi[1][0] * u0 + phi[1][1] * du0 + p[1]};
  }
  // on the stroboscopic section ωt ≡ 0 (mod 2π)
  [[nodiscard]] std::array<double, 2> section_state() const {
    return state(period_);
  }

  // 1 + tr M + det M and 1 − tr M + det M of the monodromy S Φ
  [[nodiscard]] std::array<double, 2> test_functions() const {
    const double s21 = (1.0 + o_.r) * (o_.A * std::cos(omega_ * impact_time_) - o_.sigma) / speed_;
    const auto& p = transition_;
    const double m11 = -o_.r * p[0][0], m12 = -o_.r * p[0][1];
    const double m21 = s21 * p[0][0] - o_.r * p[1][0], m22 = s21 * p[0][1] - o_.r * p[1][1];
    const double trace = m11 + m22, determinant = m11 * m22 - m12 * m21;
    return {1.0 + trace + determinant, 1.0 - trace + determinant};
  }

  // the highest point of the flight strictly between impacts: the largest x
  // at the interior roots of ẋ
  [[nodiscard]] double highest_interior() const {
    double highest = -INFINITY;
    const int grid = 2000;
    for (int k = 1; k < grid - 1; ++k) {
      const double a = impact_time_ + period_ * k / grid, b = impact_time_ + period_ * (k + 1) / grid;
      if (!(state(a)[1] > 0.0 && state(b)[1] <= 0.0)) continue;
      const double t = solve([&](double s) { return state(s)[1]; }, a, b);
      highest = std::max(highest, state(t)[0]);
    }
    return highest;
  }

 private:
  // the damped oscillator's transition matrix over τ
  [[nodiscard]] std::array<std::array<double, 2>, 2> homogeneous(double tau) const {
    const double decay = std::exp(-o_.zeta * tau);
    const double c = std::cos(wd_ * tau), s = std::sin(wd_ * tau);
    return {{{decay * (c + o_.zeta / wd_ * s), decay * s / wd_},
             {-decay * s / wd_, decay * (c - o_.zeta / wd_ * s)}}};
  }
  [[nodiscard]] std::array<double, 2> particular(double t) const {
    const double c = std::cos(omega_ * t), s = std::sin(omega_ * t);
    return {cos_amplitude_ * c + sin_amplitude_ * s,
            omega_ * (sin_amplitude_ * c - cos_amplitude_ * s)};
  }
  // the speed v that closes the position equation for an impact at t
  [[nodiscard]] double speed(double t) const {
    const auto p = particular(t);
    const double a = o_.sigma - p[0];
    const auto& m = transition_;
    return ((m[0][0] - 1.0) * a - m[0][1] * p[1]) / (o_.r * m[0][1]);
  }
  [[nodiscard]] double closing(double t) const {
    const auto p = particular(t);
    const double a = o_.sigma - p[0], v = speed(t);
    const auto& m = transition_;
    return m[1][0] * a + m[1][1] * (-o_.r * v - p[1]) - (v - p[1]);
  }

  ImpactOscillator o_;
  double omega_, period_, wd_, cos_amplitude_, sin_amplitude_;
  std::array<std::array<double, 2>, 2> transition_{};
  double impact_time_ = 0.0, speed_ = 0.0;
  bool found_ = false;
};

Scene linear_impact_scene(const ImpactOscillator& o) {
  Scene scene = impactlab::load_scene("linear_impact");
  scene.values["zeta"] = o.zeta;
  scene.values["r"] = o.r;
  scene.values["sigma"] = o.sigma;
  scene.values["A"] = o.A;
  return scene;
}

ContinuationJobResult continue_scene(const Scene& scene, const std::string& key, double from,
                                     double to, int doublings = 0,
                                     std::optional<std::array<double, 2>> start = std::nullopt) {
  ContinuationJob job;
  job.parameter = key;
  job.from = from;
  job.to = to;
  job.doublings = doublings;
  if (start) {
    job.has_start = true;
    job.start.assign(start->begin(), start->end());
  }
  return impactlab::continue_orbit(scene, job);
}

std::vector<BifurcationPoint> points_of_type(const impactlab::ContinuationResult& result,
                                             BifurcationType type) {
  std::vector<BifurcationPoint> found;
  for (const auto& point : result.points)
    if (point.type == type) found.push_back(point);
  return found;
}

double period_doubling(const ImpactOscillator& o, double a, double b) {
  return solve([&](double w) { return PeriodOneOrbit(o, w).test_functions()[0]; }, a, b);
}

TEST(Continuation, LinearImpactPeriodOneBranchUpToSeven) {
  const ImpactOscillator o;  // ζ = 0.05, r = 0.8, σ = 0, A = 1
  const Scene scene = linear_impact_scene(o);
  const PeriodOneOrbit start(o, 1.02);
  ASSERT_TRUE(start.found());
  const auto job = continue_scene(scene, "omega", 1.02, 7.0, 0, start.section_state());
  ASSERT_TRUE(job.available);
  ASSERT_EQ(job.branches.size(), 1u);
  const auto& branch = job.branches[0].result;
  EXPECT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  EXPECT_NEAR(branch.branch.back().parameter, 7.0, 1e-12);

  // the three period doublings of the closed form on [1.02, 7]
  const std::array<double, 3> expected = {period_doubling(o, 1.02, 1.05),
                                          period_doubling(o, 1.1, 1.5),
                                          period_doubling(o, 2.6, 2.7)};
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(doublings[k].located);
    EXPECT_NEAR(doublings[k].parameter, expected[k], 1e-9 * expected[k]) << k;
    EXPECT_LT(doublings[k].error_estimate, 1e-9 * expected[k]);
    EXPECT_NEAR(doublings[k].multipliers[0].real(), -1.0, 1e-7);  // |−1| > |det M|
  }
  EXPECT_TRUE(points_of_type(branch, BifurcationType::fold).empty());

  // every branch point is the closed-form orbit on the section
  for (const auto& point : branch.branch) {
    const PeriodOneOrbit closed(o, point.parameter);
    ASSERT_TRUE(closed.found()) << point.parameter;
    const auto x = closed.section_state();
    EXPECT_NEAR(point.state[0], x[0], 1e-8) << point.parameter;
    EXPECT_NEAR(point.state[1], x[1], 1e-8) << point.parameter;
    EXPECT_EQ(point.impacts, 1);
    // stability from the closed form's test functions: both multipliers real here
    const auto tests = closed.test_functions();
    EXPECT_EQ(point.stable, tests[0] > 0.0 && tests[1] > 0.0) << point.parameter;
  }
  EXPECT_GE(branch.branch.size(), 30u);
}

TEST(Continuation, LinearImpactBranchEndsAtTheGrazingWhereItIsBorn) {
  const ImpactOscillator o;
  const Scene scene = linear_impact_scene(o);
  const PeriodOneOrbit start(o, 1.5);
  ASSERT_TRUE(start.found());
  const auto job = continue_scene(scene, "omega", 1.5, 1.0, 0, start.section_state());
  const auto& branch = job.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::signature_change) << branch.stop_detail;
  const auto grazings = points_of_type(branch, BifurcationType::grazing);
  ASSERT_EQ(grazings.size(), 1u);
  // the closed form: the interior maximum of the flight reaches σ
  const double omega_graze = solve(
      [&](double w) { return PeriodOneOrbit(o, w).highest_interior() - o.sigma; }, 1.012, 1.02);
  EXPECT_NEAR(grazings[0].parameter, omega_graze, 1e-9 * omega_graze);
  EXPECT_LT(grazings[0].error_estimate, 1e-9 * omega_graze);
  // passing on the way: the two period doublings below 1.5
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 2u);
  EXPECT_NEAR(doublings[0].parameter, period_doubling(o, 1.1, 1.5), 1e-9);
  EXPECT_NEAR(doublings[1].parameter, period_doubling(o, 1.02, 1.05), 1e-9);
}

// The signatures a branch compares from point to point: a chatter ending in
// contact may resolve more or fewer impacts before its accumulation is taken
// (where the accumulation estimate takes over, not a graze), and a contact
// phase may appear or end; any other change of the walls hit is a graze.
TEST(ImpactSignature, AChattersCountAndAContactPhaseMayChangeButNoWallHit) {
  using impactlab::same_walls_hit;
  EXPECT_TRUE(same_walls_hit("+1 +1 +1 +1 c+1", "+1 +1 +1 c+1"));
  EXPECT_TRUE(same_walls_hit("-1 +1 +1 +1 +1 c+1 -1", "-1 +1 +1 +1 c+1 -1"));
  EXPECT_TRUE(same_walls_hit("-1 -1 c-1 +1 +1 c+1", "-1 -1 +1 +1"));
  EXPECT_TRUE(same_walls_hit("+1 -1", "+1 -1"));
  // a chatter that no longer ends in contact, an impact more or less, another wall
  EXPECT_FALSE(same_walls_hit("+1 +1 +1 c+1", "+1 +1 +1 +1 +1"));
  EXPECT_FALSE(same_walls_hit("+1 -1", "+1 -1 -1"));
  EXPECT_FALSE(same_walls_hit("-1 -1 c+1", "-1 c+1"));
  EXPECT_FALSE(same_walls_hit("+1 c+1", "-1 c-1"));
  // an impact before a plastic landing comes and goes by a graze
  EXPECT_FALSE(same_walls_hit("-1 -1 c-1", "-1 c-1"));
  EXPECT_FALSE(same_walls_hit("+1 +1 +1 c+1", "+1 +1 c+1"));
  EXPECT_EQ(impactlab::chatter_collapsed("-1 +1 +1 +1 c+1 -1"), "-1 +1… c+1 -1");
  EXPECT_EQ(impactlab::chatter_collapsed("-1 -1 c-1"), "-1 -1 c-1");
  EXPECT_EQ(impactlab::walls_hit("-1 +1 +1 c+1 -1"), "-1 +1 +1 -1");
}

// A branch of chattering orbits of the linear impact oscillator (r = 0.5,
// σ = 0.5: each period a flight, a chatter that accumulates on the stop, a
// contact phase until the push A cos ωt − σ falls through zero) from ω = 0.3
// to 0.4: the chatter's resolved impacts go from 13 to 12 on the way, and
// the branch runs on through to the end of its range; at three of its
// points the state is the stroboscopic point a plain run settles on (2000
// forcing periods of transient), to 1e-8.
TEST(Continuation, ABranchOfChatteringOrbitsRunsOnWhereItsResolvedImpactsChange) {
  Scene scene = impactlab::load_scene("linear_impact");
  scene.values["r"] = 0.5;
  scene.values["sigma"] = 0.5;
  const double phase = 3.14159;
  ContinuationJob job = curve_job("omega", 0.3, 0.4, "", 0.0, 0.0, CurveType::grazing);
  job.curve_type.reset();
  job.phase = phase;
  const auto result = impactlab::continue_orbit(scene, job);
  const auto& branch = result.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  ASSERT_GE(branch.branch.size(), 20u);
  int fewest = 1000, most = 0;
  for (const auto& point : branch.branch) {
    EXPECT_EQ(point.contact_phases, 1) << "omega = " << point.parameter;
    fewest = std::min(fewest, point.impacts);
    most = std::max(most, point.impacts);
  }
  EXPECT_LT(fewest, most);
  for (const std::size_t k : {std::size_t{0}, branch.branch.size() / 2, branch.branch.size() - 1}) {
    const auto& point = branch.branch[k];
    Scene at = scene;
    at.values["omega"] = point.parameter;
    impactlab::SectionRequest request;
    request.section.phase = phase;
    request.settle = false;
    request.transient_periods = 2000;
    request.points = 2;
    const impactlab::SectionResult plain = impactlab::poincare(at, request);
    ASSERT_EQ(plain.points.size(), 2u);
    EXPECT_NEAR(plain.points.back().q, point.state[0], 1e-8) << "omega = " << point.parameter;
    EXPECT_NEAR(plain.points.back().qdot, point.state[1], 1e-8) << "omega = " << point.parameter;
  }
}

// σ = 0.2: the impact speed of the period-1 orbit falls to zero as ω rises,
// where the orbit becomes the free harmonic response whose amplitude
// A/√((1 − ω²)² + (2ζω)²) just reaches the stop: the second kind of grazing.
TEST(Continuation, LinearImpactSecondParameterSetEndsWhereTheImpactSpeedVanishes) {
  ImpactOscillator o;
  o.sigma = 0.2;  // the scene's default stop
  const Scene scene = linear_impact_scene(o);
  // from the scene's own transient (no start given)
  const auto job = continue_scene(scene, "omega", 2.0, 2.5);
  const auto& branch = job.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::signature_change) << branch.stop_detail;
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 1u);
  const double expected = period_doubling(o, 2.24, 2.29);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
  const auto grazings = points_of_type(branch, BifurcationType::grazing);
  ASSERT_EQ(grazings.size(), 1u);
  const double omega_graze = solve(
      [&](double w) {
        const double detuning = 1.0 - w * w;
        return detuning * detuning + 4.0 * o.zeta * o.zeta * w * w - (o.A / o.sigma) * (o.A / o.sigma);
      },
      2.3, 2.6);
  EXPECT_NEAR(grazings[0].parameter, omega_graze, 1e-9 * omega_graze);
  EXPECT_EQ(grazings[0].note, "an impact velocity goes to zero");
}

// The same oscillator written as a model file (no C++, compiled at run time:
// oscillators/model_file/examples/linear_impact_model.toml): its continuation
// finds the closed form's period doubling and grazing as the built-in does.
TEST(Continuation, LinearImpactModelFileFindsTheClosedFormsPeriodDoublingAndGrazing) {
  const std::string cache = ::testing::TempDir() + "impactlab_continuation_model_cache";
  ASSERT_EQ(::setenv("IMPACTLAB_CACHE_DIR", cache.c_str(), 1), 0);
  ImpactOscillator o;
  o.sigma = 0.2;
  Scene scene = impactlab::load_scene(std::string(IMPACTLAB_SOURCE_DIR) +
                                      "/oscillators/model_file/examples/linear_impact_model.toml");
  ::unsetenv("IMPACTLAB_CACHE_DIR");
  scene.values["zeta"] = o.zeta;
  scene.values["r"] = o.r;
  scene.values["sigma"] = o.sigma;
  scene.values["A"] = o.A;
  const auto job = continue_scene(scene, "omega", 2.0, 2.5);
  ASSERT_TRUE(job.available) << job.note;
  const auto& branch = job.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::signature_change) << branch.stop_detail;
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 1u);
  const double expected = period_doubling(o, 2.24, 2.29);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
  EXPECT_NEAR(doublings[0].multipliers[0].real(), -1.0, 1e-7);
  const auto grazings = points_of_type(branch, BifurcationType::grazing);
  ASSERT_EQ(grazings.size(), 1u);
  const double omega_graze = solve(
      [&](double w) {
        const double detuning = 1.0 - w * w;
        return detuning * detuning + 4.0 * o.zeta * o.zeta * w * w - (o.A / o.sigma) * (o.A / o.sigma);
      },
      2.3, 2.6);
  EXPECT_NEAR(grazings[0].parameter, omega_graze, 1e-9 * omega_graze);
}

// The bouncing ball's period-doubling amplitude from Γ_pd.
double bouncing_ball_period_doubling_amplitude(double g, double omega, double r) {
  const double existence = std::numbers::pi * (1.0 - r) / (1.0 + r);
  const double stability = 2.0 * (1.0 + r * r) / ((1.0 + r) * (1.0 + r));
  const double gamma = std::sqrt(existence * existence + stability * stability);
  return gamma * g / (omega * omega);
}

// The period-1 orbit on the section t ≡ 0 (mod T): take-off at the phase φ
// with speed gT/2 from the table's height A sin φ.
std::array<double, 2> bouncing_ball_start(double g, double omega, double r, double A) {
  const double period = two_pi / omega;
  const double gamma = A * omega * omega / g;
  const double phase = std::acos(std::numbers::pi * (1.0 - r) / (gamma * (1.0 + r)));
  const double flight = period - phase / omega, speed = g * period / 2.0;
  return {A * std::sin(phase) + speed * flight - 0.5 * g * flight * flight, speed - g * flight};
}

TEST(Continuation, BouncingBallPeriodDoublingMatchesTheClosedForm) {
  const Scene scene = impactlab::load_scene("bouncing_ball");  // g 9.81, ω 30, r 0.8
  const auto job = continue_scene(scene, "A", 0.0112, 0.0125, 0,
                                  bouncing_ball_start(9.81, 30.0, 0.8, 0.0112));
  const auto& branch = job.branches.at(0).result;
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 1u) << impactlab::to_string(branch.stop_reason) << " " << branch.stop_detail;
  const double expected = bouncing_ball_period_doubling_amplitude(9.81, 30.0, 0.8);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
}

// On the impact section of the table (wall −1), which moves: the impact
// point slides along z = A sin ωt, the term ∂q_w/∂t of the map's Jacobian.
// The period-1 orbit hits the table at cos φ = π(1 − r)/(Γ(1 + r)) with
// ẏ⁻ = −gT/2; its period doubling is the closed form's.
TEST(Continuation, BouncingBallOnTheImpactSectionOfTheMovingTable) {
  const Scene scene = impactlab::load_scene("bouncing_ball");  // g 9.81, ω 30, r 0.8
  const double g = 9.81, omega = 30.0, r = 0.8, period = two_pi / omega;
  auto impact_phase = [&](double A) {
    return std::acos(std::numbers::pi * (1.0 - r) / (A * omega * omega / g * (1.0 + r)));
  };
  ContinuationJob job;
  job.parameter = "A";
  job.from = 0.0112;
  job.to = 0.0125;
  job.impact_wall = -1;
  job.has_start = true;
  job.start = {impact_phase(0.0112), -0.5 * g * period};
  const auto result = impactlab::continue_orbit(scene, job);
  const auto& branch = result.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 1u);
  const double expected = bouncing_ball_period_doubling_amplitude(g, omega, r);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
  for (const auto& point : branch.branch) {
    EXPECT_NEAR(point.state[0], impact_phase(point.parameter), 1e-9) << point.parameter;
    EXPECT_NEAR(point.state[1], -0.5 * g * period, 1e-9) << point.parameter;
  }
}

TEST(Continuation, BouncingBallCascadeThroughTwoDoublings) {
  const Scene scene = impactlab::load_scene("bouncing_ball");
  const auto job = continue_scene(scene, "A", 0.0112, 0.0135, 2,
                                  bouncing_ball_start(9.81, 30.0, 0.8, 0.0112));
  ASSERT_EQ(job.branches.size(), 3u);
  EXPECT_EQ(job.branches[1].period, 2);
  EXPECT_EQ(job.branches[2].period, 4);
  const double first = points_of_type(job.branches[0].result, BifurcationType::period_doubling).at(0).parameter;
  const double second = points_of_type(job.branches[1].result, BifurcationType::period_doubling).at(0).parameter;
  EXPECT_GT(second, first);
  EXPECT_GE(job.branches[2].result.branch.size(), 3u);
  // the doubled branch starts as two distinct points of a period-2 orbit
  const auto& doubled = job.branches[1].result.branch;
  ASSERT_GE(doubled.size(), 3u);
  EXPECT_EQ(doubled[2].impacts, 2);
}

TEST(Continuation, StableBranchPointsAgreeWithTheSweepSectionAndPeriodic) {
  const ImpactOscillator o;
  Scene scene = linear_impact_scene(o);
  const auto job = continue_scene(scene, "omega", 2.0, 2.5);
  const auto& branch = job.branches.at(0).result;
  int compared = 0;
  for (std::size_t k = 0; k < branch.branch.size(); k += 4) {
    const auto& point = branch.branch[k];
    if (!point.stable) continue;
    scene.values["omega"] = point.parameter;
    impactlab::SectionRequest request;  // strobe at phase 0 after 100 periods, as sweep does
    request.transient_periods = 600;
    request.points = 4;
    const auto section = impactlab::poincare(scene, request);
    ASSERT_FALSE(section.points.empty());
    EXPECT_NEAR(section.points.back().q, point.state[0], 1e-8) << point.parameter;
    EXPECT_NEAR(section.points.back().qdot, point.state[1], 1e-8) << point.parameter;
    impactlab::PeriodicRequest periodic;
    const auto orbit = impactlab::periodic(scene, periodic);
    ASSERT_TRUE(orbit.converged);
    EXPECT_NEAR(orbit.state[0], point.state[0], 1e-9);
    EXPECT_NEAR(orbit.state[1], point.state[1], 1e-9);
    ++compared;
  }
  EXPECT_GE(compared, 3);
}

// The impact section of the stop: the same orbit as a fixed point of the map
// from impact to impact, state (ω t* mod 2π, ẋ⁻). Multipliers of a Poincaré
// map do not depend on the section (both sections cut the same flow in the
// extended phase space (x, ẋ, ωt mod 2π) transversally), so the branch must
// have the strobe's period doubling and, at every point, the closed form's
// multipliers, the roots of λ² − tr M λ + det M of the monodromy S Φ.
TEST(Continuation, LinearImpactOnTheImpactSectionHasTheStrobesPeriodDoublingAndMultipliers) {
  ImpactOscillator o;
  o.sigma = 0.2;
  const Scene scene = linear_impact_scene(o);
  ContinuationJob job;
  job.parameter = "omega";
  job.from = 2.0;
  job.to = 2.4;  // below 2.448, where the impact itself grazes and the section degenerates
  job.impact_wall = 1;
  // the closed-form comparison below is to 1e-9: Newton to 1e-11, tighter
  // than continue's default
  job.numerics.tolerance = 1e-11;
  const auto result = impactlab::continue_orbit(scene, job);
  const auto& branch = result.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 1u);
  const double expected = period_doubling(o, 2.24, 2.29);  // 2.2652971759636387
  EXPECT_TRUE(doublings[0].located);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
  EXPECT_LT(doublings[0].error_estimate, 1e-9 * expected);
  // the strobe's branch over the same range: the same point
  const auto strobe = continue_scene(scene, "omega", 2.0, 2.4);
  const auto strobe_doublings = points_of_type(strobe.branches.at(0).result, BifurcationType::period_doubling);
  ASSERT_EQ(strobe_doublings.size(), 1u);
  EXPECT_NEAR(doublings[0].parameter, strobe_doublings[0].parameter, 1e-9 * expected);

  ASSERT_GE(branch.branch.size(), 10u);
  int compared_with_periodic = 0;
  for (std::size_t k = 0; k < branch.branch.size(); ++k) {
    const auto& point = branch.branch[k];
    const PeriodOneOrbit closed(o, point.parameter);
    ASSERT_TRUE(closed.found()) << point.parameter;
    // the state: the impact's phase and speed
    const double phase = std::fmod(point.parameter * closed.impact_time(), two_pi);
    EXPECT_NEAR(std::remainder(point.state[0] - phase, two_pi), 0.0, 1e-9) << point.parameter;
    EXPECT_NEAR(point.state[1], closed.speed(), 1e-9) << point.parameter;
    EXPECT_EQ(point.impacts, 1);
    // the multipliers against the closed form's
    const auto tests = closed.test_functions();
    const double trace = 0.5 * (tests[0] - tests[1]), determinant = 0.5 * (tests[0] + tests[1]) - 1.0;
    const std::complex<double> root =
        std::sqrt(std::complex<double>(0.25 * trace * trace - determinant));
    const std::array<std::complex<double>, 2> exact = {0.5 * trace + root, 0.5 * trace - root};
    for (const auto& multiplier : point.multipliers) {
      const double nearest = std::min(std::abs(multiplier - exact[0]), std::abs(multiplier - exact[1]));
      EXPECT_LT(nearest, 1e-9) << point.parameter << " " << multiplier;
    }
    // and against the strobe's (periodic: the stroboscopic map at the same ω)
    if (k % 5 == 0) {
      Scene at = scene;
      at.values["omega"] = point.parameter;
      const auto orbit = impactlab::periodic(at, impactlab::PeriodicRequest{});
      if (!orbit.converged) continue;  // an unstable orbit the transient does not reach
      for (const auto& multiplier : point.multipliers) {
        const double nearest = std::min(std::abs(multiplier - orbit.multipliers[0]),
                                        std::abs(multiplier - orbit.multipliers[1]));
        EXPECT_LT(nearest, 1e-9) << point.parameter;
      }
      ++compared_with_periodic;
    }
  }
  EXPECT_GE(compared_with_periodic, 1);
}

// The free (non-impacting) harmonic response x = P cos ωt + Q sin ωt of
// ẍ + 2ζẋ + x = A cos ωt: P = A(1 − ω²)/D, Q = 2ζωA/D, D = (1 − ω²)² + (2ζω)².
// Its amplitude A/√D reaches the stop σ at the grazing point, where it touches
// at the phase ωt = atan2(Q, P) of its maximum with zero speed.
double harmonic_amplitude(const ImpactOscillator& o, double omega) {
  const double detuning = 1.0 - omega * omega;
  return o.A / std::sqrt(detuning * detuning + 4.0 * o.zeta * o.zeta * omega * omega);
}
double harmonic_peak_phase(const ImpactOscillator& o, double omega) {
  const double phase = std::atan2(2.0 * o.zeta * omega, 1.0 - omega * omega);  // D > 0 cancels
  return phase < 0.0 ? phase + two_pi : phase;
}

// On the impact section of the stop, the period-1 orbit's own impact speed
// falls to zero as ω rises to the grazing point A/√D = σ: there the section
// is tangent to the flow and the impact map ends. The branch must end there
// with the point located (by the extended system on the stroboscopic map) at
// the closed form's ω to 1e-9 relative, its state the touch (the peak phase,
// rate 0) and its multipliers the free response's, e^{(−ζ ± i√(1 − ζ²))T}.
TEST(Continuation, LinearImpactOnTheImpactSectionEndsWhereItsOwnImpactSpeedVanishes) {
  ImpactOscillator o;
  o.sigma = 0.2;
  const Scene scene = linear_impact_scene(o);
  ContinuationJob job;
  job.parameter = "omega";
  job.from = 2.0;
  job.to = 2.5;
  job.impact_wall = 1;
  const auto result = impactlab::continue_orbit(scene, job);
  const auto& branch = result.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::signature_change) << branch.stop_detail;
  const auto grazings = points_of_type(branch, BifurcationType::grazing);
  ASSERT_EQ(grazings.size(), 1u) << branch.stop_detail;
  const auto& graze = grazings[0];
  const double omega_graze =
      solve([&](double w) { return harmonic_amplitude(o, w) - o.sigma; }, 2.3, 2.6);
  EXPECT_TRUE(graze.located);
  EXPECT_NEAR(graze.parameter, omega_graze, 1e-9 * omega_graze);
  EXPECT_LT(graze.error_estimate, 1e-9 * omega_graze);
  EXPECT_NE(graze.note.find("section's own impact"), std::string::npos) << graze.note;
  EXPECT_EQ(graze.graze_time, 0.0);  // touched at the section itself
  // the state on the impact section: the touch, at the peak's phase with rate 0
  EXPECT_NEAR(std::remainder(graze.state[0] - harmonic_peak_phase(o, omega_graze), two_pi), 0.0,
              1e-9);
  EXPECT_NEAR(graze.state[1], 0.0, 1e-9);
  // the multipliers of the free response over one period
  const double period = two_pi / omega_graze, wd = std::sqrt(1.0 - o.zeta * o.zeta);
  const std::complex<double> free_multiplier =
      std::exp(std::complex<double>(-o.zeta * period, wd * period));
  ASSERT_EQ(graze.multipliers.size(), 2u);
  for (const auto& multiplier : graze.multipliers) {
    const double nearest = std::min(std::abs(multiplier - free_multiplier),
                                    std::abs(multiplier - std::conj(free_multiplier)));
    EXPECT_LT(nearest, 1e-9) << multiplier;
  }
  // the branch itself runs up to the point, and the period doubling on the way
  ASSERT_FALSE(branch.branch.empty());
  EXPECT_LT(branch.branch.back().parameter, graze.parameter);
  const auto doublings = points_of_type(branch, BifurcationType::period_doubling);
  ASSERT_EQ(doublings.size(), 1u);
  const double expected = period_doubling(o, 2.24, 2.29);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
}

// The flight of ẍ + 2ζẋ + x = A cos ωt from (x0, v0) at t0, at t (closed form).
std::array<double, 2> free_flight(const ImpactOscillator& o, double omega, double t0, double x0,
                                  double v0, double t) {
  const double denominator =
      (1.0 - omega * omega) * (1.0 - omega * omega) + 4.0 * o.zeta * o.zeta * omega * omega;
  const double P = o.A * (1.0 - omega * omega) / denominator;
  const double Q = 2.0 * o.zeta * omega * o.A / denominator;
  auto particular = [&](double s) {
    return std::array<double, 2>{P * std::cos(omega * s) + Q * std::sin(omega * s),
                                 omega * (Q * std::cos(omega * s) - P * std::sin(omega * s))};
  };
  const double wd = std::sqrt(1.0 - o.zeta * o.zeta);
  const auto p0 = particular(t0), p = particular(t);
  const double c1 = x0 - p0[0], c2 = (v0 - p0[1] + o.zeta * c1) / wd;
  const double tau = t - t0, decay = std::exp(-o.zeta * tau);
  const double c = std::cos(wd * tau), s = std::sin(wd * tau);
  return {decay * (c1 * c + c2 * s) + p[0],
          decay * ((wd * c2 - o.zeta * c1) * c - (wd * c1 + o.zeta * c2) * s) + p[1]};
}

// Sticking on the stop with r = 0 (a plastic impact: the mass arrives and
// stays, x = σ, ẋ = 0, while the force on it at rest, A cos ωt − σ, pushes it
// into the stop, and is released where that push falls through zero, at
// ω t_r = arccos(σ/A) mod 2π). The period-1 orbit with one contact phase is
// then fixed: released at t_r, it flies freely from (σ, 0) and returns to the
// stop at t_i < t_r + T, where the push is positive, and sticks until t_r + T.
// As ω rises the return comes later, and the contact phase ends where it
// returns exactly at t_r + T: the root in ω of σ − x(t_r + T) on the free
// flight from (σ, 0) at t_r. Beyond it the push at the return is negative and
// the mass leaves the stop at once (no contact phase).
TEST(Continuation, ContactEndOfTheStickingOrbitLocatedAtItsClosedForm) {
  ImpactOscillator o;
  o.sigma = 0.2;
  o.r = 0.0;
  Scene scene = linear_impact_scene(o);
  auto return_gap = [&](double omega) {  // σ − x(t_r + T), the flight from (σ, 0) at t_r
    const double release = std::acos(o.sigma / o.A) / omega;
    return o.sigma - free_flight(o, omega, release, o.sigma, 0.0, release + two_pi / omega)[0];
  };
  const double expected = solve(return_gap, 1.6, 1.7);
  {  // the flight does return there first: below the stop until t_r + T
    const double release = std::acos(o.sigma / o.A) / expected, period = two_pi / expected;
    for (int k = 1; k < 1000; ++k)
      ASSERT_LT(free_flight(o, expected, release, o.sigma, 0.0, release + period * k / 1000.0)[0],
                o.sigma);
  }
  const auto job = continue_scene(scene, "omega", 1.5, 1.8);
  const auto& branch = job.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, StopReason::end_of_range) << branch.stop_detail;
  const auto ends = points_of_type(branch, BifurcationType::contact_end);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_TRUE(ends[0].located) << ends[0].note;
  EXPECT_NEAR(ends[0].parameter, expected, 1e-9 * expected);
  EXPECT_LT(ends[0].error_estimate, 1e-9 * expected);
  EXPECT_GT(ends[0].error_estimate, 0.0);
  // the monodromy vanishes there: zero on the sticking side (the release
  // forgets the state), S Φ with S ∝ the push at the return on the other
  EXPECT_LT(std::abs(ends[0].multipliers[0]), 1e-6);
  // the state: the free flight from (σ, 0) at t_r on the section ωt ≡ 0
  const double release = std::acos(o.sigma / o.A) / expected;
  const auto x = free_flight(o, expected, release, o.sigma, 0.0, two_pi / expected);
  EXPECT_NEAR(ends[0].state[0], x[0], 1e-8);
  EXPECT_NEAR(ends[0].state[1], x[1], 1e-8);
  // one contact phase before it, none after
  for (const auto& point : branch.branch) {
    if (std::fabs(point.parameter - expected) > 1e-6) {
      EXPECT_EQ(point.contact_phases, point.parameter < expected ? 1 : 0) << point.parameter;
    }
  }
  EXPECT_TRUE(points_of_type(branch, BifurcationType::contact_onset).empty());

  // run downwards, the same point is the onset of the contact phase
  const auto down = continue_scene(scene, "omega", 1.8, 1.5);
  const auto onsets = points_of_type(down.branches.at(0).result, BifurcationType::contact_onset);
  ASSERT_EQ(onsets.size(), 1u) << down.branches[0].result.stop_detail;
  EXPECT_TRUE(onsets[0].located) << onsets[0].note;
  EXPECT_NEAR(onsets[0].parameter, expected, 1e-9 * expected);
  EXPECT_LT(onsets[0].error_estimate, 1e-9 * expected);
}

// At V0 = 0.5 m/s the pendulum hangs, meeting no wall, from ω = 15 to 25:
// V0·ω = g at ω = 19.62 concerns no orbit of that branch, and is not listed
// on it (it was, as a contact_boundary)
TEST(Continuation, AHangingBranchListsNoContactBoundary) {
  Scene scene = impactlab::load_scene("jin2003");
  impactlab::apply_override(scene, "V0=0.5");
  const auto job = continue_scene(scene, "omega", 15.0, 25.0);
  const auto& result = job.branches.at(0).result;
  EXPECT_EQ(result.stop_reason, StopReason::end_of_range) << result.stop_detail;
  ASSERT_FALSE(result.branch.empty());
  EXPECT_LT(result.branch.front().parameter, 19.62);
  EXPECT_GT(result.branch.back().parameter, 19.62);
  for (const auto& point : result.branch) EXPECT_EQ(point.impacts, 0) << point.parameter;
  EXPECT_TRUE(points_of_type(result, BifurcationType::boundary).empty());
}

// jin2003 (Model N, ω = 7 rad/s, g = 9.81 m/s²): the pivot's peak
// acceleration V0·ω reaches g at V0 = g/ω, below which no contact phase can
// exist; the period-2 impacting branch continued down in V0 reports where
// it crosses it.
TEST(Continuation, PendulumBranchReportsTheContactBoundaryAtV0EqualToGOverOmega) {
  const Scene scene = impactlab::load_scene("jin2003");
  ContinuationJob job;
  job.parameter = "V0";
  job.from = 1.6;
  job.to = 1.3;
  job.period = 2;
  const auto result = impactlab::continue_orbit(scene, job);
  const auto& branch = result.branches.at(0).result.branch;
  const auto boundaries = points_of_type(result.branches[0].result, BifurcationType::boundary);
  ASSERT_EQ(boundaries.size(), 1u);
  EXPECT_EQ(impactlab::type_name(boundaries[0]), "contact_boundary");
  const double expected = scene.number("g") / scene.number("omega");
  EXPECT_NEAR(boundaries[0].parameter, expected, 1e-12 * expected);
  EXPECT_TRUE(boundaries[0].located) << boundaries[0].note;
  // the orbit there: the branch's own, between its neighbours, with impacts
  const auto after = std::find_if(branch.begin(), branch.end(),
                                  [&](const auto& p) { return p.parameter < expected; });
  ASSERT_NE(after, branch.end());
  ASSERT_NE(after, branch.begin());
  const auto before = after - 1;
  EXPECT_GT(before->impacts, 0);
  EXPECT_GT(after->impacts, 0);
  const double lower = std::min(before->state[0], after->state[0]) - 1e-6;
  const double upper = std::max(before->state[0], after->state[0]) + 1e-6;
  EXPECT_GE(boundaries[0].state[0], lower);
  EXPECT_LE(boundaries[0].state[0], upper);
}

// A continuation problem on a map written here in closed form: `evaluate`
// gives P(x; p) and its monodromy; no wall gaps, and the section stays.
template <class Evaluate>
impactlab::ContinuationProblem closed_form_problem(Evaluate evaluate) {
  impactlab::ContinuationProblem problem;
  problem.phase = 0.0;
  problem.forcing_period_at_p = two_pi;
  problem.evaluate = [evaluate](const impactlab::OrbitPoint& x, double p, double, bool,
                                const impactlab::ContactWindow&) { return evaluate(x, p); };
  problem.gap_at = [](const impactlab::OrbitPoint&, double, double,
                      const impactlab::ContactWindow&, double) { return impactlab::GapSample{}; };
  problem.transport = [](const impactlab::OrbitPoint& x, double, double, double) {
    return std::optional<impactlab::OrbitPoint>(x);
  };
  return problem;
}

// The driver on a map with a known Neimark–Sacker point: P(x; p) = c(p) +
// ρ(p) R(θ) (x − c(p)), a rotation by θ = 1 rad scaled by ρ(p) = 0.5 + p²
// about c(p) = (sin p, p²). Its fixed point is c(p), its multipliers
// ρ e^{±iθ}, a complex pair through the unit circle at p = √0.5.
TEST(Continuation, NeimarkSackerOfARotatingMapAtItsClosedForm) {
  constexpr double theta = 1.0;
  auto centre = [](double p) { return std::array<double, 2>{std::sin(p), p * p}; };
  const auto problem = closed_form_problem([&](const impactlab::OrbitPoint& x, double p) {
    impactlab::OrbitEvaluation e;
    const double rho = 0.5 + p * p;
    const auto c = centre(p);
    const double u = x[0] - c[0], v = x[1] - c[1];
    e.completed = true;
    e.image = {c[0] + rho * (std::cos(theta) * u - std::sin(theta) * v),
               c[1] + rho * (std::sin(theta) * u + std::cos(theta) * v)};
    e.monodromy = {{rho * std::cos(theta), -rho * std::sin(theta)},
                   {rho * std::sin(theta), rho * std::cos(theta)}};
    e.span = two_pi;
    e.omega = 1.0;
    return e;
  });
  impactlab::ContinuationRequest request;
  request.from = 0.2;
  request.to = 1.2;
  request.start = {0.1, 0.1};  // a guess; Newton finds c(0.2)
  request.tolerance = 1e-11;  // tighter than the default: the point is checked to 1e-12
  const auto result = impactlab::continue_branch(problem, request);
  EXPECT_EQ(result.stop_reason, StopReason::end_of_range) << result.stop_detail;
  const auto points = points_of_type(result, BifurcationType::neimark_sacker);
  ASSERT_EQ(points.size(), 1u);
  const double expected = std::sqrt(0.5);
  EXPECT_TRUE(points[0].located);
  EXPECT_NEAR(points[0].parameter, expected, 1e-12);
  EXPECT_NEAR(std::abs(points[0].multipliers[0]), 1.0, 1e-12);
  EXPECT_NEAR(std::fabs(std::arg(points[0].multipliers[0])), theta, 1e-12);
  EXPECT_NEAR(points[0].state[0], centre(expected)[0], 1e-10);
  EXPECT_NEAR(points[0].state[1], centre(expected)[1], 1e-10);
  // stable below, unstable above
  for (const auto& point : result.branch) {
    if (std::fabs(point.parameter - expected) > 1e-9) {
      EXPECT_EQ(point.stable, point.parameter < expected) << point.parameter;
    }
  }
}

// The Neimark–Sacker curve of a map written here in closed form, and its
// resonances: P(x; p₁, p₂) = c(p₁) + ρ S(p₂) (x − c(p₁)), c(p₁) = (sin p₁,
// p₁²), ρ = 0.5 + p₁² + 0.1 p₂ and S(τ) = [[τ/2, 1], [τ²/4 − 1, τ/2]]
// (det S = 1, tr S = τ). The fixed point is c(p₁); with ρ = 1 the
// multipliers are τ/2 ± √(τ²/4 − 1), a complex pair on the unit circle for
// |τ| < 2 that meets at +1 (τ = 2: 1:1 resonance) or −1 (τ = −2: 1:2) and
// leaves it as a real pair (λ, 1/λ). So the curve is p₁ = √(0.5 − 0.1 p₂),
// with its 1:1 resonance at p₂ = 2 and its 1:2 resonance at p₂ = −2.
TEST(CurveContinuation, NeimarkSackerCurveAndItsResonancesOnAMapInClosedForm) {
  auto centre = [](double p1) { return std::array<double, 2>{std::sin(p1), p1 * p1}; };
  impactlab::TwoParameterProblem problem;
  problem.at = [&](double p2) {
    return closed_form_problem([p2, centre](const impactlab::OrbitPoint& x, double p1) {
      impactlab::OrbitEvaluation e;
      const double rho = 0.5 + p1 * p1 + 0.1 * p2, tau = p2;
      const std::array<std::array<double, 2>, 2> m = {
          {{rho * tau / 2.0, rho}, {rho * (tau * tau / 4.0 - 1.0), rho * tau / 2.0}}};
      const auto c = centre(p1);
      const double u = x[0] - c[0], v = x[1] - c[1];
      e.completed = true;
      e.image = {c[0] + m[0][0] * u + m[0][1] * v, c[1] + m[1][0] * u + m[1][1] * v};
      e.monodromy = {{m[0][0], m[0][1]}, {m[1][0], m[1][1]}};
      e.span = two_pi;
      e.omega = 1.0;
      return e;
    });
  };
  const struct {
    double to2;
    impactlab::CodimensionTwoType type;
    double at2, multiplier;
  } cases[] = {{3.0, impactlab::CodimensionTwoType::resonance_1_1, 2.0, 1.0},
               {-3.0, impactlab::CodimensionTwoType::resonance_1_2, -2.0, -1.0}};
  for (const auto& one : cases) {
    impactlab::CurveRequest request;
    request.type = CurveType::neimark_sacker;
    request.from1 = 0.0;
    request.to1 = 1.0;
    request.from2 = 0.5;
    request.to2 = one.to2;
    request.p1 = 0.6;  // a guess: the curve is at √0.45 there
    request.state = {0.5, 0.4};
    const auto curve = impactlab::continue_curve(problem, request);
    EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
    ASSERT_GE(curve.curve.size(), 10u);
    for (const auto& point : curve.curve) {
      const double p1 = std::sqrt(0.5 - 0.1 * point.p2);
      EXPECT_NEAR(point.p1, p1, 1e-10) << "p2 = " << point.p2;
      EXPECT_NEAR(point.state[0], centre(p1)[0], 1e-10) << "p2 = " << point.p2;
      EXPECT_NEAR(point.state[1], centre(p1)[1], 1e-10) << "p2 = " << point.p2;
    }
    ASSERT_EQ(curve.points.size(), 1u) << "to p2 = " << one.to2;
    const auto& resonance = curve.points[0];
    EXPECT_EQ(resonance.type, one.type);
    EXPECT_TRUE(resonance.located) << resonance.note;
    EXPECT_NEAR(resonance.p2, one.at2, 1e-8);
    EXPECT_NEAR(resonance.p1, std::sqrt(0.5 - 0.1 * one.at2), 1e-8);
    ASSERT_EQ(resonance.multipliers.size(), 2u);
    for (const auto& multiplier : resonance.multipliers)
      EXPECT_NEAR(std::abs(multiplier - one.multiplier), 0.0, 1e-4);
  }
}

// A degenerate period doubling on a map written here in closed form:
// P(x, y; p₁, p₂) = (−(1 + p₁)x + p₂x³ + e x y, y/2 + d x²), fixed at the
// origin, its period-doubling curve p₁ = 0. On that curve the centre
// manifold is y = 2d x² + O(x⁴) (invariance: h(−x) = h(x)/2 + d x²), so the
// map reduced to it is x ↦ −x + (p₂ + 2ed)x³: the flip's cubic coefficient
// vanishes at p₂ = −2ed, −1 for e = 1, d = 1/2.
TEST(CurveContinuation, DegeneratePeriodDoublingOfAMapInClosedFormAtTheCentreManifoldsRoot) {
  constexpr double e = 1.0, d = 0.5;
  impactlab::TwoParameterProblem problem;
  problem.at = [&](double p2) {
    return closed_form_problem([p2](const impactlab::OrbitPoint& z, double p1) {
      impactlab::OrbitEvaluation out;
      const double x = z[0], y = z[1];
      out.completed = true;
      out.image = {-(1.0 + p1) * x + p2 * x * x * x + e * x * y, 0.5 * y + d * x * x};
      out.monodromy = {{-(1.0 + p1) + 3.0 * p2 * x * x + e * y, e * x}, {2.0 * d * x, 0.5}};
      out.span = two_pi;
      out.omega = 1.0;
      return out;
    });
  };
  impactlab::CurveRequest request;
  request.type = CurveType::period_doubling;
  request.from1 = -0.5;
  request.to1 = 0.5;
  request.from2 = 0.0;
  request.to2 = -2.0;
  request.p1 = 0.01;  // a guess: the curve is at p₁ = 0
  request.state = {0.01, 0.0};
  const auto curve = impactlab::continue_curve(problem, request);
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  for (const auto& point : curve.curve) EXPECT_NEAR(point.p1, 0.0, 1e-12) << "p2 = " << point.p2;
  ASSERT_EQ(curve.points.size(), 1u);
  const auto& degenerate = curve.points[0];
  EXPECT_EQ(degenerate.type, impactlab::CodimensionTwoType::degenerate_period_doubling);
  EXPECT_TRUE(degenerate.located) << degenerate.note;
  EXPECT_NEAR(degenerate.p1, 0.0, 1e-12);
  EXPECT_NEAR(degenerate.p2, -2.0 * e * d, 1e-6);
}

// The driver on a map whose orbit has an impact that sticks above p = 1/π
// (the count of stick impacts the map reports, as the rigid pendulum's
// impulse law does where its stick impulse enters the friction cone):
// P(x; p) = (x0 / 2 + p, x1 / 3), fixed point (2p, 0). The change is found
// between two branch points and located by bisection to 1e-10 of the range.
TEST(Continuation, StickOnsetLocatedWhereTheStickImpactsPerOrbitChange) {
  const double onset = 1.0 / std::numbers::pi;
  const auto problem = closed_form_problem([&](const impactlab::OrbitPoint& x, double p) {
    impactlab::OrbitEvaluation e;
    e.completed = true;
    e.image = {0.5 * x[0] + p, x[1] / 3.0};
    e.monodromy = {{0.5, 0.0}, {0.0, 1.0 / 3.0}};
    e.impacts = 2;
    e.stick_impacts = p > onset ? 1 : 0;
    e.span = two_pi;
    e.omega = 1.0;
    return e;
  });
  impactlab::ContinuationRequest request;
  request.from = 0.0;
  request.to = 1.0;
  request.start = {0.1, 0.1};
  const auto up = impactlab::continue_branch(problem, request);
  EXPECT_EQ(up.stop_reason, StopReason::end_of_range) << up.stop_detail;
  const auto onsets = points_of_type(up, BifurcationType::stick_onset);
  ASSERT_EQ(onsets.size(), 1u);
  EXPECT_TRUE(onsets[0].located) << onsets[0].note;
  EXPECT_NEAR(onsets[0].parameter, onset, 1e-9);
  EXPECT_LE(onsets[0].error_estimate, 1e-9);
  EXPECT_NEAR(onsets[0].state[0], 2.0 * onsets[0].parameter, 1e-9);
  EXPECT_EQ(impactlab::type_name(onsets[0]), "stick_onset");
  request.from = 1.0;
  request.to = 0.0;
  request.start = {1.9, 0.0};
  const auto down = impactlab::continue_branch(problem, request);
  const auto ends = points_of_type(down, BifurcationType::stick_end);
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_NEAR(ends[0].parameter, onset, 1e-9);
}

TEST(CurveContinuation, BouncingBallPeriodDoublingCurveInAmplitudeAndRestitution) {
  const Scene scene = impactlab::load_scene("bouncing_ball");  // g 9.81, ω 30, r 0.8
  ContinuationJob job = curve_job("A", 0.0112, 0.02, "r", 0.8, 0.5, CurveType::period_doubling);
  job.has_start = true;
  const auto start = bouncing_ball_start(9.81, 30.0, 0.8, 0.0112);
  job.start.assign(start.begin(), start.end());
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.type, CurveType::period_doubling);
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 20u);
  EXPECT_EQ(curve.curve.back().p2, 0.5);
  for (const auto& point : curve.curve) {
    const double expected = bouncing_ball_period_doubling_amplitude(9.81, 30.0, point.p2);
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "r = " << point.p2;
    EXPECT_NEAR(point.multipliers[0].real(), -1.0, 1e-7) << "r = " << point.p2;
  }
}

// The bouncing ball's impact map written here from its closed-form flight,
// independently of the toolkit: a ball leaving the table z = A sin ωt at
// time t with speed v flies on y = z(t) + v (s − t) − g (s − t)²/2 until it
// meets the table again (the first root of y − z after t, by a scan and TOMS
// 748), where ẏ⁺ = (1 + r) ż − r ẏ⁻. State (t, v after the impact).
struct BallImpactMap {
  double g = 9.81, omega = 30.0, r = 0.8, A = 0.0;
  [[nodiscard]] std::array<double, 2> operator()(const std::array<double, 2>& state) const {
    const double t = state[0], v = state[1];
    auto gap = [&](double s) {
      return A * std::sin(omega * t) + v * (s - t) - 0.5 * g * (s - t) * (s - t) -
             A * std::sin(omega * s);
    };
    const double dt = two_pi / omega / 4000.0;
    double a = t + dt;
    while (!(gap(a + dt) < 0.0)) a += dt;
    const double s = solve(gap, a, a + dt);
    const double table_rate = A * omega * std::cos(omega * s);
    return {s, (1.0 + r) * table_rate - r * (v - g * (s - t))};
  }
};

// With --switch and --param2, the curve of each doubled branch's point: the
// ball's period-2 orbit's period doubling in (A, r). Checked point by point
// on the independent impact map above: from the curve's state on the strobe
// section, the next impact; P² returns to it two forcing periods later (a
// period-2 orbit, not a period-1 one), and the Jacobian of P² (central
// differences) has a multiplier −1: det(DP² + I) = (1 + λ₁)(1 + λ₂) = 0.
TEST(CurveContinuation, BouncingBallPeriodTwoPeriodDoublingCurveWithSwitch) {
  const Scene scene = impactlab::load_scene("bouncing_ball");  // g 9.81, ω 30, r 0.8
  ContinuationJob job = curve_job("A", 0.0112, 0.025, "r", 0.8, 0.7, CurveType::period_doubling);
  job.has_start = true;
  const auto ball_start = bouncing_ball_start(9.81, 30.0, 0.8, 0.0112);
  job.start.assign(ball_start.begin(), ball_start.end());
  job.doublings = 1;
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  ASSERT_EQ(result.doubled_curves.size(), 1u);
  const auto& doubled = result.doubled_curves[0];
  ASSERT_TRUE(doubled.has_curve) << doubled.note;
  EXPECT_EQ(doubled.branch, 1);
  EXPECT_EQ(doubled.period, 2);
  EXPECT_EQ(doubled.curve.type, CurveType::period_doubling);
  EXPECT_EQ(doubled.curve.stop_reason, StopReason::end_of_range) << doubled.curve.stop_detail;
  ASSERT_GE(doubled.curve.curve.size(), 5u);
  const double period = two_pi / 30.0;
  int compared = 0;
  for (std::size_t k = 0; k < doubled.curve.curve.size(); k += 3) {
    const auto& point = doubled.curve.curve[k];
    // above the period-1 orbit's doubling at this r (the cascade's next step)
    EXPECT_GT(point.p1, bouncing_ball_period_doubling_amplitude(9.81, 30.0, point.p2));
    BallImpactMap map;
    map.r = point.p2;
    map.A = point.p1;
    // the first impact after the section t = 0, from the curve's state
    auto flight_gap = [&](double s) {
      return point.state[0] + point.state[1] * s - 0.5 * map.g * s * s -
             map.A * std::sin(map.omega * s);
    };
    double a = 0.0;
    while (!(flight_gap(a + period / 4000.0) < 0.0)) a += period / 4000.0;
    const double s = solve(flight_gap, a, a + period / 4000.0);
    const std::array<double, 2> impact = {
        s, (1.0 + map.r) * map.A * map.omega * std::cos(map.omega * s) -
               map.r * (point.state[1] - map.g * s)};
    auto twice = [&](const std::array<double, 2>& x) { return map(map(x)); };
    const auto back = twice(impact);
    EXPECT_NEAR(back[0] - impact[0], 2.0 * period, 1e-8) << "r = " << point.p2;
    EXPECT_NEAR(back[1], impact[1], 1e-8) << "r = " << point.p2;
    const auto once = map(impact);
    EXPECT_GT(std::fabs(once[1] - impact[1]), 1e-3) << "r = " << point.p2;  // not period 1
    std::array<std::array<double, 2>, 2> jacobian{};
    const std::array<double, 2> h = {1e-7 * period, 1e-7 * (1.0 + std::fabs(impact[1]))};
    for (int j = 0; j < 2; ++j) {
      auto up = impact, down = impact;
      up[j] += h[j];
      down[j] -= h[j];
      const auto a_up = twice(up), a_down = twice(down);
      for (int i = 0; i < 2; ++i) jacobian[i][j] = (a_up[i] - a_down[i]) / (2.0 * h[j]);
    }
    const double det_plus =
        (jacobian[0][0] + 1.0) * (jacobian[1][1] + 1.0) - jacobian[0][1] * jacobian[1][0];
    EXPECT_NEAR(det_plus, 0.0, 1e-5) << "r = " << point.p2;
    ++compared;
  }
  EXPECT_GE(compared, 2);
}

TEST(CurveContinuation, LinearImpactPeriodDoublingCurveInOmegaAndRestitution) {
  ImpactOscillator o;  // ζ = 0.05, σ = 0, A = 1; r from 0.8 down to 0.6
  const Scene scene = linear_impact_scene(o);
  const auto result = impactlab::continue_orbit(
      scene, curve_job("omega", 2.5, 2.8, "r", 0.8, 0.6, CurveType::period_doubling));
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  int compared = 0;
  for (std::size_t k = 0; k < curve.curve.size(); k += 4) {
    const auto& point = curve.curve[k];
    o.r = point.p2;
    // the closed form's period doubling at this r, bracketed around the point
    const double expected = period_doubling(o, point.p1 - 0.01, point.p1 + 0.01);
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "r = " << point.p2;
    const PeriodOneOrbit closed(o, point.p1);
    ASSERT_TRUE(closed.found());
    EXPECT_NEAR(point.state[0], closed.section_state()[0], 1e-8) << "r = " << point.p2;
    ++compared;
  }
  EXPECT_GE(compared, 4);
}

TEST(CurveContinuation, LinearImpactGrazingCurveInOmegaAndSigma) {
  ImpactOscillator o;
  o.sigma = 0.2;
  const Scene scene = linear_impact_scene(o);
  const auto result = impactlab::continue_orbit(
      scene, curve_job("omega", 2.0, 2.5, "sigma", 0.2, 0.4, CurveType::grazing));
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.type, CurveType::grazing);
  ASSERT_GE(curve.curve.size(), 20u);
  // ends where ω leaves [2, 2.5] (σ ≈ 0.33 at ω = 2)
  EXPECT_EQ(curve.stop_reason, StopReason::left_range) << curve.stop_detail;
  for (const auto& point : curve.curve) {
    const double detuning = 1.0 - point.p1 * point.p1;
    const double amplitude =
        o.A / std::sqrt(detuning * detuning + 4.0 * o.zeta * o.zeta * point.p1 * point.p1);
    EXPECT_NEAR(point.p2, amplitude, 1e-9 * amplitude) << "omega = " << point.p1;
  }
  EXPECT_GT(curve.curve.back().p2, 0.3);
}

// The period-doubling curve of the same branches on the impact section
// (--param2 with --section impact:1): the closed form's period doubling at
// each r to 1e-9, and the state the closed form's impact phase and speed.
TEST(CurveContinuation, LinearImpactPeriodDoublingCurveOnTheImpactSection) {
  ImpactOscillator o;  // ζ = 0.05, σ = 0, A = 1; r from 0.8 down to 0.6
  const Scene scene = linear_impact_scene(o);
  ContinuationJob job = curve_job("omega", 2.5, 2.8, "r", 0.8, 0.6, CurveType::period_doubling);
  job.impact_wall = 1;
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  EXPECT_NEAR(curve.curve.back().p2, 0.6, 1e-12);
  ASSERT_GE(curve.curve.size(), 10u);
  for (const auto& point : curve.curve) {
    o.r = point.p2;
    const double expected = period_doubling(o, point.p1 - 0.01, point.p1 + 0.01);
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "r = " << point.p2;
    const PeriodOneOrbit closed(o, point.p1);
    ASSERT_TRUE(closed.found());
    const double phase = std::fmod(point.p1 * closed.impact_time(), two_pi);
    EXPECT_NEAR(std::remainder(point.state[0] - phase, two_pi), 0.0, 1e-8) << "r = " << point.p2;
    EXPECT_GE(point.state[0], 0.0);
    EXPECT_LT(point.state[0], two_pi);
    EXPECT_NEAR(point.state[1], closed.speed(), 1e-8) << "r = " << point.p2;
  }
}

// The grazing curve of the section's own impact on the impact section, in
// (ω, σ): followed on the stroboscopic map and carried back, every point on
// A/√D = σ to 1e-9 and its state the touch (peak phase, rate 0).
TEST(CurveContinuation, LinearImpactOwnImpactGrazingCurveOnTheImpactSection) {
  ImpactOscillator o;
  o.sigma = 0.2;
  const Scene scene = linear_impact_scene(o);
  ContinuationJob job = curve_job("omega", 2.0, 2.5, "sigma", 0.2, 0.4, CurveType::grazing);
  job.impact_wall = 1;
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::left_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 20u);
  for (const auto& point : curve.curve) {
    const double amplitude = harmonic_amplitude(o, point.p1);
    EXPECT_NEAR(point.p2, amplitude, 1e-9 * amplitude) << "omega = " << point.p1;
    EXPECT_NEAR(std::remainder(point.state[0] - harmonic_peak_phase(o, point.p1), two_pi), 0.0,
                1e-9)
        << "omega = " << point.p1;
    EXPECT_NEAR(point.state[1], 0.0, 1e-9) << "omega = " << point.p1;
    EXPECT_EQ(point.graze_time, 0.0);
  }
  EXPECT_GT(curve.curve.back().p2, 0.3);
}

// The ball's period-1 orbit is born in a fold (saddle-node) where its impact
// phase reaches cos φ = 1: Γ = Aω²/g = π(1 − r)/(1 + r). Continued down in A
// on the table's impact section the branch turns there; the fold's curve in
// (A, r), r from 0.8 to 0.6, must follow A = π(1 − r)/(1 + r) g/ω² to 1e-9,
// at the impact phase 0 with ẏ⁻ = −gT/2.
TEST(CurveContinuation, BouncingBallFoldCurveOnTheImpactSection) {
  const Scene scene = impactlab::load_scene("bouncing_ball");  // g 9.81, ω 30, r 0.8
  const double g = 9.81, omega = 30.0, r = 0.8, period = two_pi / omega;
  ContinuationJob job = curve_job("A", 0.0112, 0.003, "r", 0.8, 0.6, CurveType::fold);
  job.impact_wall = -1;
  job.has_start = true;
  job.start = {std::acos(std::numbers::pi * (1.0 - r) / (0.0112 * omega * omega / g * (1.0 + r))),
               -0.5 * g * period};
  const auto result = impactlab::continue_orbit(scene, job);
  const auto folds = points_of_type(result.branches.at(0).result, BifurcationType::fold);
  ASSERT_EQ(folds.size(), 1u) << result.branches[0].result.stop_detail;
  const double fold_at = std::numbers::pi * (1.0 - r) / (1.0 + r) * g / (omega * omega);
  EXPECT_NEAR(folds[0].parameter, fold_at, 1e-9 * fold_at);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.type, CurveType::fold);
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  for (const auto& point : curve.curve) {
    const double expected = std::numbers::pi * (1.0 - point.p2) / (1.0 + point.p2) * g /
                            (omega * omega);
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "r = " << point.p2;
    EXPECT_NEAR(std::remainder(point.state[0], two_pi), 0.0, 1e-6) << "r = " << point.p2;
    EXPECT_NEAR(point.state[1], -0.5 * g * period, 1e-9) << "r = " << point.p2;
  }
}

// A cusp of folds, on a model file with its cusp in closed form
// (oscillators/model_file/examples/cusp_potential.toml): a damped particle in
// the potential of the cusp catastrophe, ẍ = a + b x − x³ − c ẋ. Its equilibria are fixed points of the stroboscopic map (T = 2π/ω), with
// multipliers e^{λT}; one is 1 where f′ = b − 3x² = 0, so the fold curve is
// (a, b) = (−2x³, 3x²) with x the fold's equilibrium, and its cusp is at
// a = b = 0, x = 0, where the other multiplier is e^{−cT}. From the fold at
// a = 2 (x = −1, b = 3) the curve must run down to the cusp, locate it there,
// and come back up the other fold, a = −2(b/3)^{3/2}, until b turns back past
// its start.
TEST(CurveContinuation, FoldCurvePassesTheCuspOfTheCuspPotentialAtTheOrigin) {
  const impactlab::testing::ScratchFolder folder;
  ASSERT_EQ(::setenv("IMPACTLAB_CACHE_DIR", (folder / "cache").c_str(), 1), 0);
  const Scene scene = impactlab::load_scene(
      std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/cusp_potential.toml");
  ::unsetenv("IMPACTLAB_CACHE_DIR");
  const auto result =
      impactlab::continue_orbit(scene, curve_job("a", -3.0, 3.0, "b", 3.0, -1.0, CurveType::fold));
  const auto folds = points_of_type(result.branches.at(0).result, BifurcationType::fold);
  ASSERT_FALSE(folds.empty());
  EXPECT_NEAR(folds[0].parameter, 2.0, 1e-9);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::left_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 20u);
  for (const auto& point : curve.curve) {
    const double x = point.state[0];
    EXPECT_NEAR(point.p1, -2.0 * x * x * x, 1e-9) << "b = " << point.p2;
    EXPECT_NEAR(point.p2, 3.0 * x * x, 1e-9) << "b = " << point.p2;
  }
  EXPECT_LT(curve.curve.back().p1, -1.9);
  EXPECT_GT(curve.curve.back().state[0], 0.9);
  ASSERT_EQ(curve.points.size(), 1u);
  const auto& cusp = curve.points[0];
  EXPECT_EQ(cusp.type, impactlab::CodimensionTwoType::cusp);
  EXPECT_TRUE(cusp.located) << cusp.note;
  EXPECT_NEAR(cusp.p1, 0.0, 1e-9);
  EXPECT_NEAR(cusp.p2, 0.0, 1e-9);
  EXPECT_NEAR(cusp.state[0], 0.0, 1e-8);
  EXPECT_NEAR(cusp.state[1], 0.0, 1e-9);
  ASSERT_EQ(cusp.multipliers.size(), 2u);
  EXPECT_NEAR(cusp.multipliers[0].real(), 1.0, 1e-9);
  EXPECT_NEAR(cusp.multipliers[1].real(), std::exp(-two_pi), 1e-9);
}

// Where the grazing scenario changes along a grazing curve. The overdamped
// linear impact oscillator (ζ = 1.2, A = 1) grazes where its harmonic
// response's amplitude A/√D(ω), D = (1 − ω²)² + 4ζ²ω², reaches the stop σ.
// The grazing orbit is the free one, whose multipliers e^{(−ζ ± √(ζ² − 1))T}
// do not depend on σ: the dominant λ₁ = e^{−(ζ − √(ζ² − 1))2π/ω} passes the
// eigenvalue rule's thresholds 1/4 at ω = 2π(ζ − √(ζ² − 1))/ln 4 and 2/3 at
// ω = 2π(ζ − √(ζ² − 1))/ln(3/2), where the predicted scenario changes from
// period adding to period adding with chaotic windows, then to chaos. The
// grazing curve from ω = 2.2 (σ = A/√D(2.2)) down in σ to 0.0125 (ω ≈ 8.9)
// must locate both, each on the closed form to 1e-9 in ω and in σ, with
// λ₁ = 1/4 and 2/3 to 1e-9; and the normal forms of grazing points located
// on branches between them must give the scenarios the points name.
TEST(CurveContinuation, GrazingScenarioChangesOfTheOverdampedOscillatorAtTheirClosedForms) {
  const double zeta = 1.2, decay = zeta - std::sqrt(zeta * zeta - 1.0);
  const auto amplitude = [&](double omega) {
    const double detuning = 1.0 - omega * omega;
    return 1.0 / std::sqrt(detuning * detuning + 4.0 * zeta * zeta * omega * omega);
  };
  Scene scene = impactlab::load_scene("linear_impact");
  scene.values["zeta"] = zeta;
  scene.values["A"] = 1.0;
  scene.values["integrator.method"] = std::string("taylor");
  scene.values["integrator.rtol"] = 1e-13;
  scene.values["integrator.atol"] = 1e-15;
  // the grazing point of the free orbit's branch in ω, falling from 9, at σ
  const auto grazing_at = [&](double sigma, const std::string& key2, double to2) {
    Scene at = scene;
    at.values["sigma"] = sigma;
    ContinuationJob job = curve_job("omega", 9.0, 2.0, key2, sigma, to2, CurveType::grazing);
    if (key2.empty()) job.curve_type.reset();
    return impactlab::continue_orbit(at, job);
  };
  const auto result = grazing_at(amplitude(2.2), "sigma", 0.0125);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  EXPECT_EQ(result.curve.stop_reason, StopReason::end_of_range) << result.curve.stop_detail;
  const std::array<double, 2> thresholds = {0.25, 2.0 / 3.0};
  ASSERT_EQ(result.curve.points.size(), thresholds.size());
  for (std::size_t k = 0; k < thresholds.size(); ++k) {
    const auto& point = result.curve.points[k];
    const double omega = 2.0 * std::numbers::pi * decay / std::log(1.0 / thresholds[k]);
    EXPECT_EQ(point.type, impactlab::CodimensionTwoType::grazing_scenario_change);
    EXPECT_TRUE(point.located) << point.note;
    EXPECT_NEAR(point.p1, omega, 1e-9 * omega);
    EXPECT_NEAR(point.p2, amplitude(omega), 1e-9 * amplitude(omega));
    EXPECT_NEAR(point.multipliers[0].real(), thresholds[k], 1e-9);
  }
  EXPECT_NE(result.curve.points[0].note.find("period_adding below, period_adding_with_chaos above"),
            std::string::npos)
      << result.curve.points[0].note;
  EXPECT_NE(result.curve.points[1].note.find("period_adding_with_chaos below, chaos above"),
            std::string::npos)
      << result.curve.points[1].note;
  // the rule at grazing points below, between and above the two (λ₁ grows with ω)
  const std::array<std::pair<double, impactlab::GrazingScenario>, 3> sides = {
      std::pair{2.3, impactlab::GrazingScenario::period_adding},
      std::pair{5.0, impactlab::GrazingScenario::period_adding_with_chaos},
      std::pair{8.7, impactlab::GrazingScenario::chaos}};
  for (const auto& [omega, scenario] : sides) {
    const auto branch = grazing_at(amplitude(omega), "", 0.0);
    const auto grazing = points_of_type(branch.branches.at(0).result, BifurcationType::grazing);
    ASSERT_EQ(grazing.size(), 1u) << "omega = " << omega;
    ASSERT_TRUE(grazing[0].normal_form.has_value()) << "omega = " << omega;
    EXPECT_NEAR(grazing[0].parameter, omega, 1e-8 * omega);
    EXPECT_EQ(grazing[0].normal_form->rule, scenario) << "omega = " << omega;
  }
}

// Where the grazing scenario changes through the sign of an impact's kick (a
// degenerate normal form), on a model file written here: two unit masses on
// ground springs 1 and 2, coupled by a spring κ, with mass-proportional
// damping c = 5 (every mode overdamped, so every multiplier is real), the
// first forced by F cos ωt and stopped at x = σ; the stop is a lever, so the
// impact's change of ẋ, −(1 + r)ẋ, comes with −β times it on ẏ. The kick on
// later gaps is the first mass's response to the velocity change ∝ (1, −β):
// Σₘ φ₁ₘ (φ₁ₘ − β φ₂ₘ) gₘ(t), gₘ > 0 the overdamped modes' impulse responses,
// φₘ the stiffness matrix's unit eigenvectors. The dominant multiplier is the
// slower mode's, so K = C P₁ E vanishes where φ₁₁/φ₂₁ = β, and there only:
// with (1 + κ − ω₁²)/κ = 1/β (ω₁² the smaller eigenvalue), κ = 2/3 for
// β = 2. Below it K > 0 and every e_k > 0 (the faster mode's share stays
// positive), so the rule is λ₁'s; above it K < 0: a jump. The graze is where
// the harmonic response's amplitude |X₁(ω, κ)| reaches σ. The grazing curve
// in (ω, κ) must locate the point at κ = 2/3 and the closed form's ω to
// 1e-9, and nothing else; and the normal forms of grazing points located on
// branches on either side must give the rules the note names.
TEST(CurveContinuation, GrazingScenarioChangesWhereTheDominantModesKickVanishes) {
  const impactlab::testing::ScratchFolder folder;
  const std::string path = (folder / "lever_stop.toml").string();
  std::ofstream(path) << R"(name = "lever_stop"
description = "two coupled overdamped masses, a lever stop on the first"
[initial]
x = 0.0
x_dot = 0.0
y = 0.0
y_dot = 0.0
[integrator]
method = "taylor"
rtol = 1e-13
atol = 1e-15
[model]
states = ["x", "x_dot", "y", "y_dot"]
forcing_frequency = "omega"
[model.parameters]
c = { default = 5.0 }
kappa = { default = 0.4 }
beta = { default = 2.0 }
F = { default = 1.0 }
omega = { default = 3.0, min = 0.0, min_open = true }
sigma = { default = 0.1 }
r = { default = 0.8, min = 0.0, max = 1.0 }
[model.rhs]
x = "x_dot"
x_dot = "F*cos(omega*t) - c*x_dot - (1 + kappa)*x + kappa*y"
y = "y_dot"
y_dot = "-c*y_dot - (2 + kappa)*y + kappa*x"
[[model.walls]]
name = "stop"
side = 1
witness = "sigma - x"
direction = "falling"
reset = { map = { x_dot = "-r*x_dot", y_dot = "y_dot + beta*(1 + r)*x_dot" } }
)";
  ASSERT_EQ(::setenv("IMPACTLAB_CACHE_DIR", (folder / "cache").c_str(), 1), 0);
  const Scene scene = impactlab::load_scene(path);
  ::unsetenv("IMPACTLAB_CACHE_DIR");
  const double c = 5.0, sigma = 0.1;
  const auto amplitude = [&](double omega, double kappa) {
    const std::complex<double> damping(0.0, omega * c);
    const std::complex<double> first = 1.0 + kappa - omega * omega + damping,
                               second = 2.0 + kappa - omega * omega + damping;
    return std::abs(second / (first * second - kappa * kappa));
  };
  const auto grazing_omega = [&](double kappa) {
    return solve([&](double omega) { return amplitude(omega, kappa) - sigma; }, 1.0, 3.0);
  };
  const auto at_kappa = [&](double kappa) {
    Scene at = scene;
    at.values["kappa"] = kappa;
    return at;
  };
  const auto result = impactlab::continue_orbit(
      at_kappa(0.4), curve_job("omega", 3.0, 1.5, "kappa", 0.4, 1.0, CurveType::grazing));
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  EXPECT_EQ(result.curve.stop_reason, StopReason::end_of_range) << result.curve.stop_detail;
  ASSERT_GE(result.curve.curve.size(), 5u);
  for (const auto& point : result.curve.curve)
    EXPECT_NEAR(point.p1, grazing_omega(point.p2), 1e-9) << "kappa = " << point.p2;
  ASSERT_EQ(result.curve.points.size(), 1u);
  const auto& point = result.curve.points[0];
  EXPECT_EQ(point.type, impactlab::CodimensionTwoType::grazing_scenario_change);
  EXPECT_TRUE(point.located) << point.note;
  EXPECT_NEAR(point.p2, 2.0 / 3.0, 1e-9);
  EXPECT_NEAR(point.p1, grazing_omega(2.0 / 3.0), 1e-9);
  EXPECT_EQ(point.note, "K = 0: period_adding_with_chaos where K > 0, jump where K < 0");
  // the rule at grazing points located on branches in ω on either side
  const std::array<std::pair<double, impactlab::GrazingScenario>, 2> sides = {
      std::pair{0.5, impactlab::GrazingScenario::period_adding_with_chaos},
      std::pair{0.8, impactlab::GrazingScenario::jump}};
  for (const auto& [kappa, scenario] : sides) {
    ContinuationJob job = curve_job("omega", 3.0, 1.5, "", 0.0, 0.0, CurveType::grazing);
    job.curve_type.reset();
    const auto branch = impactlab::continue_orbit(at_kappa(kappa), job);
    const auto grazing = points_of_type(branch.branches.at(0).result, BifurcationType::grazing);
    ASSERT_EQ(grazing.size(), 1u) << "kappa = " << kappa;
    ASSERT_TRUE(grazing[0].normal_form.has_value()) << "kappa = " << kappa;
    EXPECT_NEAR(grazing[0].parameter, grazing_omega(kappa), 1e-8) << "kappa = " << kappa;
    EXPECT_EQ(grazing[0].normal_form->rule, scenario) << "kappa = " << kappa;
    EXPECT_EQ(grazing[0].normal_form->dominant_product > 0.0, kappa < 2.0 / 3.0)
        << "kappa = " << kappa;
  }
}

// A grazing–period-doubling point: on the curve in (ω, σ) where the flight's
// interior maximum touches the stop, the virtual orbit (the one-impact
// period-1 orbit whose flight touches) has a multiplier through −1 where the
// period-doubling curve of that orbit meets the grazing curve. Closed form:
// for each σ the grazing ω_g(σ) is the root of the highest interior point
// minus σ, and the point is the root in σ of 1 + tr M + det M at (ω_g(σ), σ).
// The closed form's grazing–period-doubling point of the one-impact
// period-1 orbit below σ = 0 (o's σ aside): the grazing ω(σ), where the
// flight's interior maximum reaches σ, and the root in σ of 1 + tr M + det M
// of the closed-form monodromy at that ω.
std::pair<double, double> grazing_period_doubling_omega_sigma(const ImpactOscillator& o) {
  auto grazing_omega = [&](double sigma) {
    ImpactOscillator at = o;
    at.sigma = sigma;
    return solve([&](double w) { return PeriodOneOrbit(at, w, false).highest_interior() - sigma; },
                 1.0, 1.1);
  };
  auto doubling_test = [&](double sigma) {
    ImpactOscillator at = o;
    at.sigma = sigma;
    return PeriodOneOrbit(at, grazing_omega(sigma), false).test_functions()[0];
  };
  const double sigma = solve(doubling_test, -0.03, -0.02);
  return {grazing_omega(sigma), sigma};
}

// A located grazing–period-doubling point of o's one-impact orbit on that
// closed form to 1e-8: both parameters, the multiplier −1, and its state the
// closed form's virtual orbit there (the orbit that touches the stop).
void expect_grazing_period_doubling_at_closed_form(const impactlab::CodimensionTwoPoint& point,
                                                   const ImpactOscillator& o) {
  const auto [omega_expected, sigma_expected] = grazing_period_doubling_omega_sigma(o);
  EXPECT_EQ(point.type, impactlab::CodimensionTwoType::grazing_period_doubling);
  EXPECT_TRUE(point.located) << point.note;
  EXPECT_NEAR(point.p1, omega_expected, 1e-8);
  EXPECT_NEAR(point.p2, sigma_expected, 1e-8);
  EXPECT_LT(point.error_estimate, 1e-8);
  EXPECT_NEAR(point.multipliers[0].real(), -1.0, 1e-7);
  ImpactOscillator at = o;
  at.sigma = sigma_expected;
  const PeriodOneOrbit virtual_orbit(at, omega_expected, false);
  EXPECT_NEAR(point.state[0], virtual_orbit.section_state()[0], 1e-8);
  EXPECT_NEAR(point.state[1], virtual_orbit.section_state()[1], 1e-8);
  EXPECT_TRUE(std::isfinite(point.graze_time));
}

TEST(CurveContinuation, LinearImpactGrazingPeriodDoublingPointAtItsClosedForm) {
  ImpactOscillator o;  // ζ = 0.05, r = 0.8, A = 1; σ from 0 downwards
  Scene scene = linear_impact_scene(o);
  scene.values["initial.x"] = -0.5;  // inside the stop down to σ = −0.04
  ContinuationJob job = curve_job("omega", 1.5, 0.8, "sigma", 0.0, -0.04, CurveType::grazing);
  job.has_start = true;
  const auto start = PeriodOneOrbit(o, 1.5).section_state();
  job.start.assign(start.begin(), start.end());
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  EXPECT_EQ(result.curve.stop_reason, StopReason::end_of_range) << result.curve.stop_detail;
  ASSERT_EQ(result.curve.points.size(), 1u);
  expect_grazing_period_doubling_at_closed_form(result.curve.points[0], o);
}

// The same point from the other curve: the period-doubling curve of the
// branch's lower period doubling (ω = 1.03997 at σ = 0) runs down in σ into
// the graze. Past it the one-impact orbit penetrates the stop, and a
// two-impact orbit with a multiplier −1 lies next to it: the curve must stop
// at the grazing–period-doubling point, located on the closed form to 1e-8,
// every point of it a one-impact orbit; --switch there follows the grazing
// curve.
TEST(CurveContinuation, PeriodDoublingCurveStopsWhereItMeetsTheGrazeAtItsClosedForm) {
  ImpactOscillator o;  // ζ = 0.05, r = 0.8, A = 1; σ from 0 downwards
  const double sigma_expected = grazing_period_doubling_omega_sigma(o).second;
  const Scene scene = linear_impact_scene(o);
  ContinuationJob job =
      curve_job("omega", 1.09, 0.8, "sigma", 0.0, -0.04, CurveType::period_doubling);
  job.has_start = true;
  const auto start = PeriodOneOrbit(o, 1.09).section_state();
  job.start.assign(start.begin(), start.end());
  job.doublings = 1;  // --switch
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  EXPECT_EQ(result.curve.stop_reason, StopReason::signature_change) << result.curve.stop_detail;
  ASSERT_GE(result.curve.curve.size(), 10u);
  for (const auto& point : result.curve.curve) {
    EXPECT_EQ(point.impacts, 1) << "sigma = " << point.p2;
    EXPECT_GT(point.p2, sigma_expected);
  }
  ASSERT_EQ(result.curve.points.size(), 1u);
  expect_grazing_period_doubling_at_closed_form(result.curve.points[0], o);
  // the switch there follows the grazing curve, back towards σ = 0, on the
  // closed form's grazing ω(σ)
  ASSERT_EQ(result.switched_curves.size(), 1u);
  const auto& switched = result.switched_curves[0];
  ASSERT_TRUE(switched.has_curve) << switched.note;
  EXPECT_EQ(switched.curve.type, CurveType::grazing);
  EXPECT_EQ(switched.curve.stop_reason, StopReason::end_of_range) << switched.curve.stop_detail;
  ASSERT_GE(switched.curve.curve.size(), 5u);
  EXPECT_EQ(switched.curve.curve.back().p2, 0.0);
  for (const auto& on_graze : switched.curve.curve) {
    ImpactOscillator graze = o;
    graze.sigma = on_graze.p2;
    EXPECT_NEAR(PeriodOneOrbit(graze, on_graze.p1, false).highest_interior(), on_graze.p2, 1e-9)
        << "sigma = " << on_graze.p2;
  }
}

// With switch, the period-doubling curve through that point: followed from
// it back to σ = 0, every point on the closed form's period doubling (the
// root in ω of 1 + tr M + det M at its σ) and admissible (its flight stays
// below the stop), ending at σ = 0 on the branch's lower period doubling.
TEST(CurveContinuation, SwitchAtAGrazingPeriodDoublingPointFollowsThePeriodDoublingCurve) {
  const ImpactOscillator o;
  Scene scene = linear_impact_scene(o);
  scene.values["initial.x"] = -0.5;
  ContinuationJob job = curve_job("omega", 1.5, 0.8, "sigma", 0.0, -0.04, CurveType::grazing);
  job.has_start = true;
  const auto start = PeriodOneOrbit(o, 1.5).section_state();
  job.start.assign(start.begin(), start.end());
  job.doublings = 1;
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  ASSERT_EQ(result.curve.points.size(), 1u);
  ASSERT_EQ(result.switched_curves.size(), 1u);
  const auto& switched = result.switched_curves[0];
  ASSERT_TRUE(switched.has_curve) << switched.note;
  EXPECT_EQ(switched.started_at, impactlab::CodimensionTwoType::grazing_period_doubling);
  EXPECT_EQ(switched.curve.type, CurveType::period_doubling);
  EXPECT_EQ(switched.curve.stop_reason, StopReason::end_of_range) << switched.curve.stop_detail;
  ASSERT_GE(switched.curve.curve.size(), 5u);
  EXPECT_NEAR(switched.curve.curve.front().p2, result.curve.points[0].p2, 1e-9);
  EXPECT_EQ(switched.curve.curve.back().p2, 0.0);
  for (std::size_t k = 1; k < switched.curve.curve.size(); ++k) {
    const auto& point = switched.curve.curve[k];
    ImpactOscillator at = o;
    at.sigma = point.p2;
    const double expected = period_doubling(at, point.p1 - 0.005, point.p1 + 0.005);
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "sigma = " << point.p2;
    EXPECT_TRUE(PeriodOneOrbit(at, point.p1).found()) << "sigma = " << point.p2;
  }
  EXPECT_NEAR(switched.curve.curve.back().p1, period_doubling(o, 1.02, 1.05), 1e-9);
}

// A curve type asked for that the branch has no located point of is bad
// input naming `curve` and the type (the run writes nothing).
TEST(CurveContinuation, NoPointOfTheTypeOnTheBranchIsBadInputNamingCurve) {
  const ImpactOscillator o;
  const Scene scene = linear_impact_scene(o);
  ContinuationJob job = curve_job("omega", 3.0, 4.0, "r", 0.8, 0.6, CurveType::fold);  // no fold up to 7
  job.has_start = true;
  const auto start = PeriodOneOrbit(o, 3.0).section_state();
  job.start.assign(start.begin(), start.end());
  try {
    impactlab::continue_orbit(scene, job);
    FAIL() << "no BadInput";
  } catch (const impactlab::BadInput& error) {
    EXPECT_EQ(error.key(), "curve");
    EXPECT_EQ(error.value(), "fold");
  }
}

}  // namespace
