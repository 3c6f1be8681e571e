// The pendulum between walls as a rigid-body scene (model = "rigid",
// oscillators/pendulum_walls/rigid_pendulum_walls.hpp), run through the
// library exactly as the command line runs it:
// * reduction: spin locked and radius 0 reproduce Model N's impact sequence
//   (times, angular velocities, normal impulses) and its contact events
//   (start, slip reversals, release: times, normal forces, friction work) to
//   1e-9, over the paper's scene with chattering and sliding-contact phases;
//   a radius of 1e-12 m stays within 1e-9 of it over a shorter span;
// * the default model of the pendulum stays Model N;
// * spin free: every impact obeys θ̇⁺ = −e_n θ̇⁻ (γ_N depends on θ̇ alone), and
//   the tangential velocity change is the one the impulse equations give by
//   hand: γ_T⁺ = −e_t γ_T⁻ where the ball sticks (then |P_T| ≤ μ P_N), otherwise
//   the sliding friction −μ s P_N acting on rod and ball;
// * bad combinations of radius and spin are BadInput.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/scene.hpp>
#include <impactlab/oscillators/pendulum_walls/rigid_pendulum_walls.hpp>
#include <impactlab/rigidbody/contact_phase.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

RunOutput run_scene(const std::vector<std::string>& assignments, double periods) {
  Scene scene = load_scene("jin2003");
  for (const auto& assignment : assignments) apply_override(scene, assignment);
  RunRequest request;
  request.periods = periods;
  return run_of_scene(scene, request);
}

std::vector<EventRecord> impacts_of(const RunOutput& output) {
  std::vector<EventRecord> impacts;
  for (const auto& e : output.events)
    if (e.kind == EventKind::impact) impacts.push_back(e);
  return impacts;
}

void expect_same_impacts(const RunOutput& newton, const RunOutput& rigid, double tolerance) {
  const auto a = impacts_of(newton), b = impacts_of(rigid);
  ASSERT_GT(a.size(), 20u);
  ASSERT_EQ(a.size(), b.size());
  double worst_t = 0.0, worst_qdot = 0.0, worst_impulse = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].wall, b[i].wall) << "impact " << i;
    worst_t = std::max(worst_t, std::fabs(a[i].t - b[i].t));
    worst_qdot = std::max({worst_qdot, std::fabs(a[i].qdot_before - b[i].qdot_before),
                           std::fabs(a[i].qdot_after - b[i].qdot_after)});
    worst_impulse = std::max(worst_impulse, std::fabs(a[i].normal_impulse - b[i].normal_impulse));
  }
  EXPECT_LE(worst_t, tolerance);
  EXPECT_LE(worst_qdot, tolerance);
  EXPECT_LE(worst_impulse, tolerance);
  EXPECT_EQ(newton.contact_phases, rigid.contact_phases);
  EXPECT_EQ(newton.accumulations, rigid.accumulations);
}

TEST(RigidPendulum, LockedSpinZeroRadiusReproducesModelN) {
  // V0 = 1.5 m/s: impacts only; V0 = 4.163 m/s (the paper's Fig. 4c): g_e
  // changes sign, the impacts chatter, accumulate and a sliding contact follows
  const RunOutput newton = run_scene({}, 60.0);
  const RunOutput rigid = run_scene({"model=rigid", "spin=locked", "radius=0"}, 60.0);
  EXPECT_EQ(rigid.termination, impactlab::Termination::completed);
  expect_same_impacts(newton, rigid, 1e-9);

  // V0 = 7 m/s: contact phases with slip reversals (the pivot's velocity
  // changes sign while the bob rests on the wall)
  for (const std::string v0 : {"V0=4.163", "V0=7"}) {
    const RunOutput newton_contact = run_scene({v0}, 20.0);
    const RunOutput rigid_contact = run_scene({v0, "model=rigid", "radius=0"}, 20.0);
    ASSERT_GT(newton_contact.contact_phases, 0u) << v0;
    expect_same_impacts(newton_contact, rigid_contact, 1e-9);
    // the contact phases themselves: start, slip reversals and release (an
    // event exactly at the end time is kept by a directional witness, the
    // rigid model's, and not by an `either` one, Model N's: left out)
    const double before_end = newton_contact.t_end - 1e-9;
    std::vector<EventRecord> a, b;
    for (const auto& e : newton_contact.events)
      if (e.kind != EventKind::impact && e.t < before_end) a.push_back(e);
    for (const auto& e : rigid_contact.events)
      if (e.kind != EventKind::impact && e.t < before_end) b.push_back(e);
    ASSERT_EQ(a.size(), b.size()) << v0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].kind, b[i].kind) << v0 << " event " << i;
      EXPECT_NEAR(a[i].t, b[i].t, 1e-9) << v0 << " event " << i;
      if (!std::isnan(a[i].normal_force)) {
        EXPECT_NEAR(a[i].normal_force, b[i].normal_force, 1e-9) << v0 << " event " << i;
      }
      if (!std::isnan(a[i].friction_work)) {
        EXPECT_NEAR(a[i].friction_work, b[i].friction_work, 1e-9) << v0 << " event " << i;
      }
    }
  }
}

TEST(RigidPendulum, LockedSpinTinyRadiusStaysWithinTheReductionTolerance) {
  const RunOutput newton = run_scene({"V0=4.163"}, 10.0);
  const RunOutput rigid = run_scene({"V0=4.163", "model=rigid", "spin=locked", "radius=1e-12"}, 10.0);
  expect_same_impacts(newton, rigid, 1e-9);
}

TEST(RigidPendulum, DefaultModelIsTheOneDegreeOfFreedomModel) {
  const Scene scene = load_scene("jin2003");
  EXPECT_EQ(scene.text("model"), "newton");
  const RunOutput output = run_scene({}, 2.0);
  EXPECT_FALSE(output.derived.contains("ball_inertia_kg_m2"));
  for (const auto& e : output.events) EXPECT_TRUE(std::isnan(e.tangential_velocity_after));
}

void expect_free_spin_impacts_follow_the_hand_impulse_equations(double e_t) {
  const double m = 0.5, l = 0.7, b = 0.05, r = 0.01, e_n = 0.3, mu = 0.6;
  const double ball_inertia = 0.4 * m * r * r, sin0 = (b - r) / l;
  const double cos0 = std::sqrt(1.0 - sin0 * sin0);
  const RunOutput rigid = run_scene(
      {"model=rigid", "spin=free", "radius=0.01", "e_t=" + std::to_string(e_t)}, 30.0);
  const auto impacts = impacts_of(rigid);
  ASSERT_GT(impacts.size(), 20u);
  int sticks = 0, slides = 0;
  for (const auto& e : impacts) {
    const double w = e.wall;
    EXPECT_NEAR(e.qdot_after, -e_n * e.qdot_before, 1e-12);
    // rod: m l² Δθ̇ = W_N P_N + W_T,θ P_T with W_N = −w l cos θ0, W_T,θ = −w l sin θ0
    const double p_n = e.normal_impulse;
    const double p_t = (m * l * l * (e.qdot_after - e.qdot_before) + w * l * cos0 * p_n) /
                       (-w * l * sin0);
    EXPECT_GE(p_n, 0.0);
    if (e.sticks) {
      ++sticks;
      EXPECT_NEAR(e.tangential_velocity_after, -e_t * e.tangential_velocity, 1e-9);
      EXPECT_LE(std::fabs(p_t), mu * p_n * (1.0 + 1e-9));
      continue;
    }
    ++slides;
    // slide: P_T = −μ s P_N; ball: I_b Δφ̇ = −w r P_T; Δγ_T = −l sin θ Δθ̇ − w r Δφ̇
    const double s = e.tangential_velocity > 0 ? 1.0 : -1.0;
    const double p_t_slide = -mu * s * p_n;
    EXPECT_NEAR(p_t, p_t_slide, 1e-9 * (1.0 + std::fabs(p_n)));
    const double delta_phi_dot = -w * r * p_t_slide / ball_inertia;
    const double delta_gamma =
        -w * l * sin0 * (e.qdot_after - e.qdot_before) - w * r * delta_phi_dot;
    EXPECT_NEAR(e.tangential_velocity_after - e.tangential_velocity, delta_gamma, 1e-9);
    EXPECT_GT(e.tangential_velocity_after * e.tangential_velocity, 0.0);  // no reversal
  }
  EXPECT_GT(sticks, 0) << "e_t = " << e_t;  // both branches of the impulse law were checked
  EXPECT_GT(slides, 0) << "e_t = " << e_t;
  EXPECT_TRUE(rigid.derived.contains("emergent_e_t_median"));
}

TEST(RigidPendulum, FreeSpinImpactsFollowTheHandImpulseEquations) {
  expect_free_spin_impacts_follow_the_hand_impulse_equations(0.0);
  expect_free_spin_impacts_follow_the_hand_impulse_equations(-0.1);
  expect_free_spin_impacts_follow_the_hand_impulse_equations(-0.5);
}

// The generalized contact of the pendulum through the contact-phase solver,
// against the forces solved by hand from m l² θ̈ = h_θ + W_N λ_N + W_T,θ λ_T
// with θ̈ = 0 (and, sticking, I_b φ̈ = −w r λ_T with γ̇_T = 0).
TEST(RigidPendulum, ContactForcesAreTheHandSolutions) {
  RigidPendulumParameters p;
  p.pendulum.V0 = 4.163;
  p.radius = 0.01;
  const double m = 0.5, l = 0.7, b = 0.05, g = 9.81, w_forcing = 7.0, mu = 0.6;
  const double sin0 = (b - p.radius) / l, cos0 = std::sqrt(1.0 - sin0 * sin0);
  const double t = 0.1;  // g_e = g − V0 ω cos ωt < 0: the wall attracts
  const double g_e = g - p.pendulum.V0 * w_forcing * std::cos(w_forcing * t);
  ASSERT_LT(g_e, 0.0);
  for (const int wall : {1, -1}) {
    // spin locked, sliding with the pivot: W_T,θ = −w (l sin θ0 + r)
    p.spin_free = false;
    p.pendulum.mu = mu;
    const RigidPendulumWalls locked(p);
    const RigidPendulumWalls::State resting{wall * locked.wall_angle(), 0.0, 0.0, 0.0, 0.0};
    const double slip = p.pendulum.V0 * std::sin(w_forcing * t);
    const double s = slip > 0 ? 1.0 : -1.0;
    const auto sliding = rigidbody::contact_forces<1>(locked.locked_spin_contact(wall, resting, t),
                                                      mu, slip, 0.0);
    ASSERT_EQ(sliding.regime, rigidbody::ContactRegime::slide);
    EXPECT_NEAR(sliding.normal, -m * g_e * sin0 / (cos0 - s * mu * (sin0 + p.radius / l)), 1e-12);
    EXPECT_NEAR(sliding.tangential, -mu * s * sliding.normal, 1e-12);

    // spin free, rolling with the pivot: λ_T = −I_b V0 ω cos ωt / r²,
    // λ_N = −m g_e tan θ0 − tan θ0 λ_T; this needs |λ_T| ≤ μ λ_N, so a
    // rough wall (μ tan θ0 < 1 still)
    p.spin_free = true;
    p.pendulum.mu = 8.0;
    ASSERT_LT(p.pendulum.mu * sin0 / cos0, 1.0);
    const RigidPendulumWalls free_spin(p);
    const double ball_inertia = 0.4 * m * p.radius * p.radius;
    RigidPendulumWalls::State rolling = resting;
    rolling[RigidPendulumWalls::spin_rate] = wall * slip / p.radius;  // γ_T = V0 sin ωt − w r φ̇ = 0
    const double lambda_t =
        -ball_inertia * p.pendulum.V0 * w_forcing * std::cos(w_forcing * t) / (p.radius * p.radius);
    const double lambda_n = -m * g_e * sin0 / cos0 - sin0 / cos0 * lambda_t;
    ASSERT_LE(std::fabs(lambda_t), p.pendulum.mu * lambda_n);
    const auto sticking = rigidbody::contact_forces<2>(
        free_spin.free_spin_contact(wall, rolling, t), p.pendulum.mu, 0.0, 1e-12);
    ASSERT_EQ(sticking.regime, rigidbody::ContactRegime::stick) << "wall " << wall;
    EXPECT_NEAR(sticking.tangential, lambda_t, 1e-12);
    EXPECT_NEAR(sticking.normal, lambda_n, 1e-12);

    // at μ = 0.6 the same rolling state cannot stick: the slip starts
    // opposite to the friction the rolling would need
    const auto slipping = rigidbody::contact_forces<2>(
        free_spin.free_spin_contact(wall, rolling, t), mu, 0.0, 1e-12);
    ASSERT_EQ(slipping.regime, rigidbody::ContactRegime::slide);
    EXPECT_EQ(slipping.slip_sign, lambda_t > 0 ? -1.0 : 1.0);
    EXPECT_NEAR(slipping.normal, -m * g_e * sin0 / (cos0 - slipping.slip_sign * mu * sin0), 1e-12);
  }
}

// Regression: a slide that started from a stick (or a stop of the slip) with
// the slip at zero to round-off took its friction direction from the sign of
// that round-off, hovered at γ_T = 0 and crawled through 6 million steps;
// the slip direction is now the mode's. On a rough wall (μ = 15) the ball
// rolls on the wall in every contact phase and the run takes as many steps as
// on a smooth one, where it never rolls.
TEST(RigidPendulum, RollingContactsDoNotCrawl) {
  RunRequest request;
  request.periods = 50.0;
  request.sample_step = 1e-3;
  const auto run_with = [&](const std::string& mu) {
    Scene scene = load_scene("jin2003");
    for (const std::string assignment : {"model=rigid", "spin=free", "radius=0.01", "V0=5"})
      apply_override(scene, assignment);
    apply_override(scene, "mu=" + mu);
    return run_of_scene(scene, request);
  };
  const RunOutput rough = run_with("15");
  const RunOutput smooth = run_with("0.6");
  EXPECT_EQ(rough.termination, impactlab::Termination::completed);
  EXPECT_GT(rough.contact_phases, 40u);
  std::size_t rolling = 0, rolling_smooth = 0;
  for (const auto& sample : rough.samples) rolling += sample.mode.starts_with("stick") ? 1 : 0;
  for (const auto& sample : smooth.samples) rolling_smooth += sample.mode.starts_with("stick") ? 1 : 0;
  EXPECT_GT(rolling, 1000u);
  EXPECT_EQ(rolling_smooth, 0u);
  EXPECT_LT(rough.steps, 2 * smooth.steps);
}

// A slip that stops on the friction cone's edge, where the cone margin is
// falling, slides on instead of sticking for no time: sticking there handed
// the same instant back and forth between a stick's break and a slide's
// stop, and these runs stopped with no_progress (at t = 37.9, 61.2, 42.4
// and 18.1 s). Each now completes its 150 periods, rolling on the way.
TEST(RigidPendulum, SlipStoppingOnTheConesEdgeSlidesOn) {
  RunRequest request;
  request.periods = 150.0;
  request.sample_step = 2e-3;
  for (const std::string mu : {"9", "10", "13", "17"}) {
    Scene scene = load_scene("jin2003");
    for (const std::string& assignment : std::vector<std::string>{
             "model=rigid", "spin=free", "radius=0.01", "V0=5", "mu=" + mu})
      apply_override(scene, assignment);
    const RunOutput run = run_of_scene(scene, request);
    EXPECT_EQ(run.termination, impactlab::Termination::completed) << "mu = " << mu;
    std::size_t rolling = 0;
    for (const auto& sample : run.samples) rolling += sample.mode.starts_with("stick") ? 1 : 0;
    EXPECT_GT(rolling, 100u) << "mu = " << mu;
  }
}

// A ball that rolls on the wall (stick) until the friction it needs leaves
// the cone, on the Taylor stepper (the scene's default), whose witnesses are
// polynomials: the two cone edges μ λ_N ∓ λ_T are separate smooth witnesses
// so that no step carries |λ_T| past its kink. Each stick ends where the
// closed-form forces of rolling (λ_T = −I_b V0 ω cos ωt / r², λ_N = −m g_e
// tan θ0 − tan θ0 λ_T; rigid_pendulum_walls.hpp) put λ_T on the cone's edge,
// and the whole event sequence is rkf78's at the same tolerance.
TEST(RigidPendulum, StickEndsOnTheConeEdgeOnTheTaylorStepper) {
  const std::vector<std::string> rolling = {"model=rigid", "spin=free", "radius=0.01", "V0=5",
                                            "mu=15"};
  std::vector<std::string> taylor_run = rolling, rkf78_run = rolling;
  taylor_run.push_back("integrator.method=taylor");
  rkf78_run.push_back("integrator.method=rkf78");
  const RunOutput taylor = run_scene(taylor_run, 20.0);
  const RunOutput rkf78 = run_scene(rkf78_run, 20.0);
  ASSERT_EQ(taylor.termination, impactlab::Termination::completed);

  const Scene scene = load_scene("jin2003");
  const double m = scene.number("m"), l = scene.number("l"), b = scene.number("b"),
               g = scene.number("g"), omega = scene.number("omega"), V0 = 5.0, mu = 15.0,
               r = 0.01;
  const double ball_inertia = 0.4 * m * r * r;
  const double tan0 = std::tan(std::asin((b - r) / l));
  // μ λ_N − |λ_T| of rolling at time t (N)
  const auto cone_margin = [&](double t) {
    const double tangential = -ball_inertia * V0 * omega * std::cos(omega * t) / (r * r);
    const double normal = -m * (g - V0 * omega * std::cos(omega * t)) * tan0 - tan0 * tangential;
    return mu * normal - std::fabs(tangential);
  };
  int on_edge = 0, inside = 0;
  for (const auto& e : taylor.events) {
    if (e.kind != EventKind::slip_reversal) continue;
    // a stick that starts is inside the cone; one that ends is on its edge
    // (forces of order 10 N: 1e-9 N is the time error times their rate)
    const double margin = cone_margin(e.t);
    if (std::fabs(margin) < 1e-9)
      ++on_edge;
    else if (margin > 1e-3)
      ++inside;
    else
      ADD_FAILURE() << "slip reversal at t = " << e.t << " with cone margin " << margin;
  }
  EXPECT_GE(on_edge, 10);
  EXPECT_EQ(on_edge, inside);  // every stick that starts ends within the run

  ASSERT_EQ(taylor.events.size(), rkf78.events.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < taylor.events.size(); ++i) {
    EXPECT_EQ(taylor.events[i].kind, rkf78.events[i].kind) << "event " << i;
    worst = std::max(worst, std::fabs(taylor.events[i].t - rkf78.events[i].t));
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(RigidPendulum, RadiusMustFitAndSpinNeedsARadius) {
  EXPECT_EQ(testing::bad_input_key([] { run_scene({"model=rigid", "radius=0.05"}, 1.0); }),
            "radius");
  EXPECT_EQ(
      testing::bad_input_key([] { run_scene({"model=rigid", "spin=free", "radius=0"}, 1.0); }),
      "spin");
  try {
    run_scene({"model=rigid", "radius=0.06"}, 1.0);
    FAIL() << "no BadInput";
  } catch (const BadInput& bad) {
    EXPECT_EQ(bad.key(), "radius");
    EXPECT_EQ(bad.value(), "0.06");
  }
}

}  // namespace
}  // namespace impactlab
