// The curve of a contact phase's end in two parameters (--param2 with
// --curve contact_end; analysis/curve_continuation.hpp with the landing push
// of analysis/contact_landing.hpp) against its closed form, written here
// independently of the toolkit.
//
// The linear impact oscillator ẍ + 2ζẋ + x = A cos ωt with a plastic stop
// (r = 0) at x = σ: the mass that reaches the stop stays on it while the push
// A cos ωt − σ is positive and is released where the push falls through zero,
// ω t_r = arccos(σ/A). Its period-1 orbit with a contact phase is released at
// t_r, flies freely from (σ, 0) and returns to the stop before t_r + T, and
// the contact phase ends where the return comes exactly at t_r + T: at each
// σ, the root in ω of σ − x(t_r + T) on the free flight from (σ, 0) at t_r
// (TOMS 748), the flight below the stop before it. Every point of the curve
// must lie on it to 1e-9 in ω, with the closed form's state on the section
// (the stroboscopic one, and the impact section of the stop).
//
// The same on the bouncing ball's moving table (r = 0), against its
// closed form Aω² = g √(1 + π²). The pendulum's contact boundary V0·ω = g
// (--curve contact_boundary), a condition on the parameters alone, against
// V0 = g/ω and brute-force runs (the last test).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <boost/math/tools/roots.hpp>
#include <gtest/gtest.h>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

#include "support/curve_job.hpp"
#include "support/pendulum_plain_run.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::testing::curve_job;

using impactlab::BifurcationType;
using impactlab::ContinuationJob;
using impactlab::CurveType;
using impactlab::Scene;
using impactlab::StopReason;

constexpr double two_pi = 2.0 * std::numbers::pi;
constexpr double zeta = 0.05, amplitude = 1.0;

// The flight of ẍ + 2ζẋ + x = A cos ωt from (x0, v0) at t0, at t (closed form:
// the damped homogeneous solution plus the harmonic response).
std::array<double, 2> free_flight(double omega, double t0, double x0, double v0, double t) {
  const double detuning = 1.0 - omega * omega;
  const double denominator = detuning * detuning + 4.0 * zeta * zeta * omega * omega;
  const double P = amplitude * detuning / denominator;
  const double Q = 2.0 * zeta * omega * amplitude / denominator;
  auto particular = [&](double s) {
    return std::array<double, 2>{P * std::cos(omega * s) + Q * std::sin(omega * s),
                                 omega * (Q * std::cos(omega * s) - P * std::sin(omega * s))};
  };
  const double wd = std::sqrt(1.0 - zeta * zeta);
  const auto p0 = particular(t0), p = particular(t);
  const double c1 = x0 - p0[0], c2 = (v0 - p0[1] + zeta * c1) / wd;
  const double tau = t - t0, decay = std::exp(-zeta * tau);
  const double c = std::cos(wd * tau), s = std::sin(wd * tau);
  return {decay * (c1 * c + c2 * s) + p[0],
          decay * ((wd * c2 - zeta * c1) * c - (wd * c1 + zeta * c2) * s) + p[1]};
}

double release_time(double omega, double sigma) { return std::acos(sigma / amplitude) / omega; }

// σ − x(t_r + T): the gap one forcing period after the release
double return_gap(double omega, double sigma) {
  const double release = release_time(omega, sigma);
  return sigma - free_flight(omega, release, sigma, 0.0, release + two_pi / omega)[0];
}

// The contact end at σ nearest `near` in ω: the sign change of the return
// gap on a grid of 1e-3 around it, then TOMS 748 to the last bits.
double contact_end_omega(double sigma, double near) {
  const double step = 1e-3;
  for (int k = 0; k < 100; ++k) {
    for (const double a : {near + k * step, near - (k + 1) * step}) {
      const double b = a + step;
      if (return_gap(a, sigma) * return_gap(b, sigma) > 0.0) continue;
      std::uintmax_t iterations = 300;
      const auto bracket = boost::math::tools::toms748_solve(
          [&](double omega) { return return_gap(omega, sigma); }, a, b,
          boost::math::tools::eps_tolerance<double>(50), iterations);
      return 0.5 * (bracket.first + bracket.second);
    }
  }
  return NAN;
}

Scene plastic_stop_scene() {
  Scene scene = impactlab::load_scene("linear_impact");
  scene.values["zeta"] = zeta;
  scene.values["A"] = amplitude;
  scene.values["r"] = 0.0;
  scene.values["sigma"] = 0.2;
  return scene;
}

ContinuationJob contact_end_job(double sigma_to) {
  return curve_job("omega", 1.5, 1.8, "sigma", 0.2, sigma_to, CurveType::contact_end);
}

TEST(ContactBoundaryCurve, ContactEndOfThePlasticStopInOmegaAndSigmaAtItsClosedForm) {
  const auto result = impactlab::continue_orbit(plastic_stop_scene(), contact_end_job(0.35));
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.type, CurveType::contact_end);
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  EXPECT_DOUBLE_EQ(curve.curve.front().p2, 0.2);
  EXPECT_DOUBLE_EQ(curve.curve.back().p2, 0.35);
  for (const auto& point : curve.curve) {
    const double expected = contact_end_omega(point.p2, point.p1);
    ASSERT_TRUE(std::isfinite(expected)) << "sigma = " << point.p2;
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "sigma = " << point.p2;
    // the flight from the release stays below the stop until t_r + T: the
    // root is the orbit's first return
    const double release = release_time(expected, point.p2), period = two_pi / expected;
    for (int k = 1; k < 200; ++k)
      ASSERT_LT(free_flight(expected, release, point.p2, 0.0, release + period * k / 200.0)[0],
                point.p2)
          << "sigma = " << point.p2;
    // the state on the section ωt ≡ 0: the flight from (σ, 0) at t_r, at T
    const auto x = free_flight(expected, release, point.p2, 0.0, period);
    EXPECT_NEAR(point.state[0], x[0], 1e-8) << "sigma = " << point.p2;
    EXPECT_NEAR(point.state[1], x[1], 1e-8) << "sigma = " << point.p2;
    // the monodromy vanishes on the curve (the release forgets the state)
    EXPECT_LT(std::abs(point.multipliers[0]), 1e-6) << "sigma = " << point.p2;
  }
}

// The same curve on the impact section (impact:1): the state is the landing
// itself, the phase ω t_r (mod 2π) = arccos(σ/A) and the rate just before it,
// ẋ(t_r + T) of the flight from (σ, 0) at t_r.
TEST(ContactBoundaryCurve, ContactEndOnTheImpactSectionAtItsClosedForm) {
  ContinuationJob job = contact_end_job(0.35);
  job.impact_wall = 1;
  const auto result = impactlab::continue_orbit(plastic_stop_scene(), job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  for (const auto& point : curve.curve) {
    const double expected = contact_end_omega(point.p2, point.p1);
    ASSERT_TRUE(std::isfinite(expected)) << "sigma = " << point.p2;
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "sigma = " << point.p2;
    const double release = release_time(expected, point.p2);
    EXPECT_NEAR(point.state[0], std::acos(point.p2 / amplitude), 1e-9) << "sigma = " << point.p2;
    const auto before = free_flight(expected, release, point.p2, 0.0, release + two_pi / expected);
    EXPECT_NEAR(point.state[1], before[1], 1e-8) << "sigma = " << point.p2;
  }
}

TEST(ContactBoundaryCurve, ATypeTheBranchHasNoPointOfIsBadInputNamingCurve) {
  // the branch of the plastic stop from ω = 1.5 to 1.8 has a contact end, no
  // contact onset, no parameter boundary (the oscillator supplies none) and
  // no Neimark–Sacker point
  for (const CurveType type :
       {CurveType::contact_onset, CurveType::contact_boundary, CurveType::neimark_sacker}) {
    ContinuationJob job = contact_end_job(0.3);
    job.curve_type = type;
    try {
      impactlab::continue_orbit(plastic_stop_scene(), job);
      ADD_FAILURE() << "no BadInput for " << impactlab::to_string(type);
    } catch (const impactlab::BadInput& error) {
      EXPECT_EQ(error.key(), "curve");
      EXPECT_EQ(error.value(), impactlab::to_string(type));
      EXPECT_NE(std::string(error.what()).find("contact_end"), std::string::npos) << error.what();
    }
  }
}

// The bouncing ball with a plastic impact (r = 0) on its table z = A sin ωt:
// it rides the table while the push g + z̈ is positive and is released where
// A ω² sin ωt_r = g (the table moving up), flies the parabola from (z, ż) at
// t_r and lands on the table plastically. Its period-1 orbit lands again
// before t_r + T and rides the table to the next release; the contact phase
// ends where the landing comes exactly at t_r + T: z(t_r + T) = z(t_r) on the
// parabola gives ż(t_r) = gT/2 = πg/ω, and with sin ωt_r = g/(Aω²),
// A ω² = g √(1 + π²) (Γ = √(1 + π²), the classical sticking threshold).
// The branch in A at ω = 30 rad/s must locate the contact end there to 1e-9,
// and the curve in (A, ω) must lie on it to 1e-9 with the parabola's state
// on the section ωt ≡ 2.4 rad (in the flight) to 1e-8, until A leaves its range.
TEST(ContactBoundaryCurve, BouncingBallContactEndAtGammaEqualToRootOfOnePlusPiSquared) {
  Scene scene = impactlab::load_scene("bouncing_ball");
  scene.values["r"] = 0.0;
  const double g = scene.number("g");
  const double threshold = std::sqrt(1.0 + std::numbers::pi * std::numbers::pi);
  const auto amplitude_at = [&](double omega) { return g * threshold / (omega * omega); };
  ContinuationJob job = curve_job("A", 0.03, 0.04, "omega", 30.0, 40.0, CurveType::contact_end);
  job.phase = 2.4;  // rad: in the flight
  const auto result = impactlab::continue_orbit(scene, job);
  const auto ends =
      std::count_if(result.branches.at(0).result.points.begin(),
                    result.branches[0].result.points.end(), [](const auto& point) {
                      return point.type == BifurcationType::contact_end && point.located;
                    });
  EXPECT_EQ(ends, 1);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  ASSERT_GE(curve.curve.size(), 10u) << curve.stop_detail;
  EXPECT_NEAR(curve.curve.front().p1, amplitude_at(30.0), 1e-9 * amplitude_at(30.0));
  // A falls as 1/ω² along the curve: it leaves [0.03, 0.04] at ω ≈ 32.9
  EXPECT_EQ(curve.stop_reason, StopReason::left_range) << curve.stop_detail;
  EXPECT_GT(curve.curve.back().p2, 32.5);
  for (const auto& point : curve.curve) {
    const double omega = point.p2, expected = amplitude_at(omega);
    EXPECT_NEAR(point.p1, expected, 1e-9 * expected) << "omega = " << omega;
    const double release = std::asin(1.0 / threshold) / omega, period = two_pi / omega;
    const double y0 = expected * std::sin(omega * release);
    const double v0 = expected * omega * std::cos(omega * release);
    const auto flight = [&](double t) {
      const double tau = t - release;
      return std::array<double, 2>{y0 + v0 * tau - 0.5 * g * tau * tau, v0 - g * tau};
    };
    // the flight stays above the table until it lands at t_r + T
    for (int k = 1; k < 200; ++k) {
      const double t = release + period * k / 200.0;
      ASSERT_GT(flight(t)[0], expected * std::sin(omega * t)) << "omega = " << omega;
    }
    const auto x = flight(2.4 / omega);
    EXPECT_NEAR(point.state[0], x[0], 1e-8) << "omega = " << omega;
    EXPECT_NEAR(point.state[1], x[1], 1e-8) << "omega = " << omega;
    EXPECT_LT(std::abs(point.multipliers[0]), 1e-6) << "omega = " << omega;
  }
}

// On the scene's own section ωt ≡ 0 the same orbit rides the table, so the
// section map, which runs from a flight, has no start there: bad input
// naming `param`, with the section as the remedy.
TEST(ContactBoundaryCurve, AnOrbitRestingOnTheTableAtTheSectionIsRefusedNamingTheSection) {
  Scene scene = impactlab::load_scene("bouncing_ball");
  scene.values["r"] = 0.0;
  ContinuationJob job = curve_job("A", 0.03, 0.04, "omega", 30.0, 40.0, CurveType::contact_end);
  try {
    impactlab::continue_orbit(scene, job);
    FAIL() << "no BadInput";
  } catch (const impactlab::BadInput& error) {
    EXPECT_EQ(error.key(), "param");
    EXPECT_NE(std::string(error.what()).find("rests on a wall at the section"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("`section`"), std::string::npos) << error.what();
  }
}

// The pendulum's V0·ω = g (the pivot's peak acceleration reaches g; below
// it no contact phase can exist) followed as a curve (--curve
// contact_boundary): jin2003's period-2 impacting orbit, continued down in V0
// at ω = 7 rad/s, crosses it at V0 = g/ω; the curve runs from there to
// ω = 6.6 in (V0, ω). Every point must lie on V0 = g/ω (the closed form) to
// 1e-12, and where the orbit is stable its state must be one of the
// stroboscopic points that a plain run from the scene's initial state
// settles on (2000 forcing periods of transient), to 1e-8.
TEST(ContactBoundaryCurve, PendulumV0OmegaEqualToGIsFollowedOnItsClosedForm) {
  const Scene scene = impactlab::load_scene("jin2003");
  ContinuationJob job = curve_job("V0", 1.6, 1.3, "omega", 7.0, 6.6, CurveType::contact_boundary);
  job.period = 2;
  const auto result = impactlab::continue_orbit(scene, job);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.type, CurveType::contact_boundary);
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  EXPECT_DOUBLE_EQ(curve.curve.front().p2, 7.0);
  EXPECT_DOUBLE_EQ(curve.curve.back().p2, 6.6);
  const double g = scene.number("g");
  int compared = 0;
  for (const auto& point : curve.curve) {
    EXPECT_NEAR(point.p1, g / point.p2, 1e-12 * g / point.p2) << "omega = " << point.p2;
    EXPECT_EQ(point.impacts, 2) << "omega = " << point.p2;
    if (std::abs(point.multipliers[0]) > 0.97 || compared == 3) continue;
    ++compared;
    Scene at = scene;
    at.values["V0"] = point.p1;
    at.values["omega"] = point.p2;
    impactlab::SectionRequest request;
    request.settle = false;
    request.transient_periods = 2000;
    request.points = 4;
    const impactlab::SectionResult plain = impactlab::poincare(at, request);
    ASSERT_EQ(plain.points.size(), 4u);
    double nearest = INFINITY;
    for (const impactlab::SectionPoint& strobe : plain.points)
      nearest = std::min(nearest, std::max(std::fabs(strobe.q - point.state[0]),
                                           std::fabs(strobe.qdot - point.state[1])));
    EXPECT_LE(nearest, 1e-8) << "omega = " << point.p2;
  }
  EXPECT_EQ(compared, 3);
}

// The pendulum's contact end with plastic walls (jin2003, e_n = 0), in
// (V0, ω). Its symmetric period-2 orbit leaves each wall where the pivot's
// effective gravity g_e = g − V0 ω cos ωt rises through zero (the contact
// phase's release witness, the frictionless normal force −m g_e tan θ0,
// falls through zero) and lands on the other; below the curve in V0 it lands
// where the wall no longer holds it, and no contact phase remains. Checked
// against plain runs of the same scene from the curve's states: each lands,
// within its two periods, where g_e = 0 to 1e-9 of g (the push is a closed
// form of the landing time); 1e-3 above the curve in V0 the run has contact
// phases, 1e-3 below none.
TEST(ContactBoundaryCurve, PendulumWithPlasticWallsEndsItsContactWhereItLandsAsTheWallLetsGo) {
  Scene scene = impactlab::load_scene("jin2003");
  scene.values["e_n"] = 0.0;
  scene.values["V0"] = 2.0;
  const double phase = 3.0, g = scene.number("g");
  ContinuationJob job = curve_job("V0", 2.0, 1.3, "omega", 7.0, 6.6, CurveType::contact_end);
  job.period = 2;
  job.phase = phase;
  const auto result = impactlab::continue_orbit(scene, job);
  std::vector<impactlab::BifurcationPoint> ends;
  for (const auto& point : result.branches.at(0).result.points)
    if (point.type == BifurcationType::contact_end) ends.push_back(point);
  ASSERT_EQ(ends.size(), 1u);
  ASSERT_TRUE(result.has_curve) << result.curve_note;
  const auto& curve = result.curve;
  EXPECT_EQ(curve.stop_reason, StopReason::end_of_range) << curve.stop_detail;
  ASSERT_GE(curve.curve.size(), 10u);
  EXPECT_NEAR(curve.curve.front().p1, ends[0].parameter, 1e-9);
  // a plain run from the section state at (V0, ω)
  const auto run_from = [&](const auto& point, double v0, double periods) {
    return impactlab::testing::pendulum_run_from(scene, point.state, v0, point.p2, phase,
                                                 periods);
  };
  for (std::size_t k = 0; k < curve.curve.size(); k += curve.curve.size() / 4) {
    const auto& point = curve.curve[k];
    const double v0 = point.p1, omega = point.p2;
    const auto plain = run_from(point, v0, 2.0);
    double nearest = INFINITY;
    for (const impactlab::EventRecord& event : plain.events) {
      const bool landing =
          event.kind == impactlab::EventKind::accumulation ||
          (event.kind == impactlab::EventKind::impact && event.qdot_after == 0.0);
      if (landing)
        nearest = std::min(nearest, std::fabs(g - v0 * omega * std::cos(omega * event.t)));
    }
    EXPECT_LE(nearest, 1e-9 * g) << "omega = " << omega;
    for (const double offset : {1e-3, -1e-3}) {
      const auto nearby = run_from(point, v0 + offset, 20.0);
      const auto contacts = std::count_if(
          nearby.events.begin(), nearby.events.end(), [&](const impactlab::EventRecord& event) {
            return event.kind == impactlab::EventKind::contact_start &&
                   event.t > nearby.t0 + 10.0 * 2.0 * std::numbers::pi / omega;
          });
      if (offset > 0.0)
        EXPECT_GT(contacts, 0) << "omega = " << omega;
      else
        EXPECT_EQ(contacts, 0) << "omega = " << omega;
    }
  }
}

}  // namespace
