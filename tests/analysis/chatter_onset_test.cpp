// The onset of complete chatter (analysis/chatter_onset.hpp), located on a
// branch and followed as a curve (--curve chatter_onset), against a reference
// written here independently of the toolkit.
//
// The self-similar chatter: the local model's hop, integrated here as the
// cubic gap y(σ) = v σ − c s σ²/2 + c σ³/6 (its root by bisection, not the
// quadratic formula the header solves), returns the scaled speed u* onto
// itself, with remaining times shrinking by ρ, and the map's derivative
// there (central differences) is μ.
//
// The onset. The linear impact oscillator ẍ + 2ζẋ + x = A cos ωt against a
// stop at x = σ with restitution r: its period-1 orbit with a contact phase
// is released where the push A cos ωt − σ falls through zero, ω t_r =
// arccos(σ/A), flies from (σ, 0), returns to the stop and chatters. Below
// the onset in ω the chatter accumulates before t_r + T (a contact phase
// follows), above it the mass escapes. The reference follows the closed-form
// flight in long double, impact by impact (tests/support/
// linear_impact_chatter.hpp), and classifies each ω by where the chatter
// goes; bisection on that class gives the onset to about 1e-14.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include <gtest/gtest.h>

#include <impactlab/analysis/chatter_onset.hpp>
#include <impactlab/analysis/continuation.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/io/scene.hpp>

#include "support/curve_job.hpp"
#include "support/linear_impact_chatter.hpp"
#include "support/pendulum_plain_run.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::BifurcationType;
using impactlab::ContinuationJob;
using impactlab::CurveType;
using impactlab::Scene;
using impactlab::StopReason;

// The hop of the local model from time-to-go s (c = 1) with speed v: its
// length and the speed it lands with, the cubic's first positive root by
// bisection.
std::array<double, 2> local_hop(double s, double v) {
  const auto gap = [&](double t) { return v * t - s * t * t / 2.0 + t * t * t / 6.0; };
  // the gap is positive from 0 to its first root, which lies before the
  // minimum of the quadratic part's slope (t = s)
  double low = 1e-3 * v / s, high = s;
  if (!(gap(high) < 0.0)) return {NAN, NAN};
  for (int k = 0; k < 200; ++k) {
    const double middle = 0.5 * (low + high);
    (gap(middle) > 0.0 ? low : high) = middle;
  }
  const double t = 0.5 * (low + high);
  return {t, std::fabs(v - s * t + t * t / 2.0)};
}

// u ↦ r v'/s'² of the local hop, from s = 1
double scaled_map(double u, double r) {
  const auto [length, landing_speed] = local_hop(1.0, u);
  return r * landing_speed / ((1.0 - length) * (1.0 - length));
}

TEST(SelfSimilarChatter, ItsScaledSpeedIsAFixedPointOfTheLocalHopUnstableWithItsMultiplier) {
  for (const double r : {0.2, 0.5, 0.8, 0.95}) {
    const auto chatter = impactlab::self_similar_chatter(r);
    ASSERT_TRUE(chatter) << r;
    const double u = chatter->scaled_speed;
    EXPECT_NEAR(scaled_map(u, r), u, 1e-12 * u) << r;
    EXPECT_NEAR(local_hop(1.0, u)[0], chatter->hop_fraction, 1e-12) << r;
    EXPECT_DOUBLE_EQ(chatter->remaining_ratio, 1.0 - chatter->hop_fraction) << r;
    const double h = 1e-6 * u;
    const double slope = (scaled_map(u + h, r) - scaled_map(u - h, r)) / (2.0 * h);
    EXPECT_NEAR(slope, chatter->multiplier, 1e-6 * chatter->multiplier) << r;
    EXPECT_GT(chatter->multiplier, 1.0) << r;
    EXPECT_NEAR(std::pow(chatter->multiplier, chatter->index), 1e4, 1e-6) << r;
    // below u* the chatter drifts to u → 0, above it to no landing at all
    EXPECT_LT(scaled_map(0.9 * u, r), 0.9 * u) << r;
    EXPECT_GT(scaled_map(1.1 * u, r), 1.1 * u) << r;
  }
  EXPECT_FALSE(impactlab::self_similar_chatter(0.0));
  EXPECT_FALSE(impactlab::self_similar_chatter(1.0));
}

constexpr double zeta = 0.05, amplitude = 1.0, restitution = 0.5;

// +1: the chatter after the release accumulates before the next release;
// −1: it escapes; 0: undecided after 60 impacts.
int chatter_class(long double omega, long double sigma) {
  impactlab::testing::ChatterParameters p;
  p.zeta = zeta;
  p.amplitude = amplitude;
  p.sigma = sigma;
  p.restitution = restitution;
  return impactlab::testing::reference_chatter(p, omega, 60).side;
}

// The onset in ω between `below` (accumulates) and `above` (escapes).
double reference_onset(double sigma, double below, double above) {
  long double low = below, high = above;
  EXPECT_EQ(chatter_class(low, sigma), 1) << "sigma = " << sigma;
  EXPECT_EQ(chatter_class(high, sigma), -1) << "sigma = " << sigma;
  for (int k = 0; k < 70; ++k) {
    const long double middle = 0.5L * (low + high);
    const int side = chatter_class(middle, sigma);
    if (side == 0) break;
    (side > 0 ? low : high) = middle;
  }
  return static_cast<double>(0.5L * (low + high));
}

Scene chattering_scene(double sigma) {
  Scene scene = impactlab::load_scene("linear_impact");
  scene.values["zeta"] = zeta;
  scene.values["A"] = amplitude;
  scene.values["r"] = restitution;
  scene.values["sigma"] = sigma;
  return scene;
}

ContinuationJob chattering_branch(double phase) {
  ContinuationJob job;
  job.parameter = "omega";
  job.from = 0.3;
  job.to = 0.5;
  job.phase = phase;
  return job;
}

TEST(ChatterOnset, TheBranchOfChatteringOrbitsEndsAtTheOnsetOfCompleteChatter) {
  const auto result = impactlab::continue_orbit(chattering_scene(0.5), chattering_branch(3.14159));
  ASSERT_FALSE(result.branches.empty());
  const auto& branch = result.branches.front().result;
  const impactlab::BifurcationPoint* onset = nullptr;
  for (const auto& point : branch.points)
    if (point.type == BifurcationType::chatter_onset) onset = &point;
  ASSERT_NE(onset, nullptr) << branch.stop_detail;
  ASSERT_TRUE(onset->located);
  const double expected = reference_onset(0.5, 0.46, 0.47);
  EXPECT_NEAR(onset->parameter, expected, 1e-9);
  EXPECT_LE(std::fabs(onset->parameter - expected), onset->error_estimate);
  EXPECT_LT(onset->error_estimate, 1e-8);
  // the orbit forgets its state at the release: its multipliers vanish
  for (const auto& multiplier : onset->multipliers) EXPECT_LT(std::abs(multiplier), 1e-6);
}

TEST(ChatterOnset, ItsCurveInOmegaAndSigmaLiesOnTheReference) {
  ContinuationJob job =
      impactlab::testing::curve_job("omega", 0.3, 0.5, "sigma", 0.5, 0.56, CurveType::chatter_onset);
  job.phase = 3.14159;
  const auto result = impactlab::continue_orbit(chattering_scene(0.5), job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.type, CurveType::chatter_onset);
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 5u);
  EXPECT_DOUBLE_EQ(curve.curve.back().p2, 0.56);
  const std::size_t count = curve.curve.size();
  for (const std::size_t i : {std::size_t{0}, count / 3, 2 * count / 3, count - 1}) {
    const auto& point = curve.curve[i];
    const double expected = reference_onset(point.p2, point.p1 - 1e-4, point.p1 + 1e-4);
    EXPECT_NEAR(point.p1, expected, 1e-9) << "sigma = " << point.p2;
  }
}

// The pendulum (jin2003) with e_n = 0.3: its symmetric period-2 orbit
// chatters into a contact phase on each wall and is released where the
// pivot's effective gravity rises through zero. Below V0 ≈ 4.25 the chatter
// escapes. Its onset, located on the branch from V0 = 5 down and followed in
// (V0, ω), is checked against plain runs of the scene from the located
// states: 1e-5 above each point in V0 a run of two periods has a contact
// phase on each wall, 1e-5 below it none.
TEST(ChatterOnset, ThePendulumsChatterIntoContactStopsCompletingWherePlainRunsSayItDoes) {
  Scene scene = impactlab::load_scene("jin2003");
  scene.values["e_n"] = 0.3;
  scene.values["V0"] = 5.0;
  const double phase = 3.0;
  ContinuationJob job = impactlab::testing::curve_job("V0", 5.0, 1.3, "omega", 7.0, 6.8,
                                                      CurveType::chatter_onset);
  job.period = 2;
  job.phase = phase;
  const auto result = impactlab::continue_orbit(scene, job);
  const impactlab::BifurcationPoint* onset = nullptr;
  for (const auto& point : result.branches.at(0).result.points)
    if (point.type == BifurcationType::chatter_onset) onset = &point;
  ASSERT_NE(onset, nullptr) << result.branches.at(0).result.stop_detail;
  EXPECT_LT(onset->error_estimate, 1e-8);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 5u);
  EXPECT_NEAR(curve.curve.front().p1, onset->parameter, 1e-9);
  const auto contact_phases = [&](const impactlab::CurvePoint& point, double v0) {
    const auto run =
        impactlab::testing::pendulum_run_from(scene, point.state, v0, point.p2, phase, 2.0);
    return std::count_if(run.events.begin(), run.events.end(), [](const auto& event) {
      return event.kind == impactlab::EventKind::contact_start;
    });
  };
  for (const std::size_t i : {std::size_t{0}, curve.curve.size() / 2, curve.curve.size() - 1}) {
    const auto& point = curve.curve[i];
    EXPECT_EQ(contact_phases(point, point.p1 * (1.0 + 1e-5)), 2) << "omega = " << point.p2;
    EXPECT_EQ(contact_phases(point, point.p1 * (1.0 - 1e-5)), 0) << "omega = " << point.p2;
  }
}

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
