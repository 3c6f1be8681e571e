// The accumulation estimate of contact/accumulation.hpp and the accumulation
// times of whole runs, each against a reference computed here independently:
// * the local model (constant-rate drift of the acceleration, damping)
//   integrated flight by flight in long double;
// * the bouncing ball on a fixed table, whose accumulation time is the sum
//   of a geometric series in closed form;
// * jin2003 at V0 = 4.163 m/s (chatter into a contact phase), against an
//   event loop written here in long double: classical Runge-Kutta at a fixed
//   10 µs step (shorter in the short flights), impacts located by bisection
//   on single steps, the chatter followed until its flights are 0.1 µs long
//   and closed by the constant-acceleration tail (whose error is then below
//   1e-13 s).
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/contact/accumulation.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/api/system_jobs.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

// --- the local model: z̈ = −(a + ȧ s) − c ż, restitution r ------------------

struct ModelChatter {
  long double a, a_rate, damping, r;
};

// Time from the first separation (speed u) to the accumulation point, by
// classical Runge-Kutta on each flight (200 steps), the impact found by
// bisection on the last step; the tail after flights of 1e-12 s is summed as
// a geometric series.
long double model_accumulation_time(const ModelChatter& m, long double u) {
  auto accel = [&](long double s, long double v) { return -(m.a + m.a_rate * s) - m.damping * v; };
  long double s = 0.0L;
  for (;;) {
    const long double a_now = m.a + m.a_rate * s;
    const long double flight = 2.0L * u / a_now;
    if (flight < 1e-12L) return s + flight / (1.0L - m.r);
    const long double h = flight / 200.0L;
    long double z = 0.0L, v = u, t = s;
    auto step = [&](long double t0, long double z0, long double v0, long double dt, long double& z1,
                    long double& v1) {
      const long double k1z = v0, k1v = accel(t0, v0);
      const long double k2z = v0 + 0.5L * dt * k1v, k2v = accel(t0 + 0.5L * dt, k2z);
      const long double k3z = v0 + 0.5L * dt * k2v, k3v = accel(t0 + 0.5L * dt, k3z);
      const long double k4z = v0 + dt * k3v, k4v = accel(t0 + dt, k4z);
      z1 = z0 + dt / 6.0L * (k1z + 2.0L * k2z + 2.0L * k3z + k4z);
      v1 = v0 + dt / 6.0L * (k1v + 2.0L * k2v + 2.0L * k3v + k4v);
    };
    for (int i = 0;; ++i) {
      long double z1, v1;
      step(t, z, v, h, z1, v1);
      if (i > 0 && z1 < 0.0L) {
        long double lo = 0.0L, hi = h;
        for (int k = 0; k < 80; ++k) {
          const long double mid = 0.5L * (lo + hi);
          step(t, z, v, mid, z1, v1);
          (z1 < 0.0L ? hi : lo) = mid;
        }
        step(t, z, v, hi, z1, v1);
        s = t + hi;
        u = -m.r * v1;
        break;
      }
      t += h;
      z = z1;
      v = v1;
    }
  }
}

struct ModelCase {
  double r, a_rate, damping, u;
};

class AccumulationEstimate : public ::testing::TestWithParam<ModelCase> {};

// The first-order estimate is within its error bound, and far closer than
// the constant-acceleration sum 2u/(a(1 − r)).
TEST_P(AccumulationEstimate, IsWithinItsBoundOfTheIntegratedModel) {
  const ModelCase c = GetParam();
  const double a = 1.0;
  const long double reference =
      model_accumulation_time({a, c.a_rate, c.damping, c.r}, static_cast<long double>(c.u));
  const auto estimate = estimate_accumulation({c.u, a, c.a_rate, c.r, 0.0, c.damping, 0.0});
  ASSERT_TRUE(estimate);
  const double error = std::fabs(estimate->remaining - static_cast<double>(reference));
  const double constant_error =
      std::fabs(2.0 * c.u / (a * (1.0 - c.r)) - static_cast<double>(reference));
  EXPECT_LE(error, estimate->error_bound + 1e-15) << "reference " << static_cast<double>(reference);
  EXPECT_LT(error, 0.1 * constant_error);
}

INSTANTIATE_TEST_SUITE_P(
    Model, AccumulationEstimate,
    ::testing::Values(ModelCase{0.0, 0.02, 0.0, 0.01}, ModelCase{0.3, 0.02, 0.0, 0.007},
                    ModelCase{0.3, -0.02, 0.0, 0.007}, ModelCase{0.8, 0.02, 0.0, 0.002},
                    ModelCase{0.3, 0.0, 0.03, 0.007}, ModelCase{0.6, 0.01, 0.02, 0.004}));

// A diverging or repelling sequence has no accumulation.
TEST(AccumulationEstimate, NeedsAnAttractingWallAndRestitutionBelowOne) {
  EXPECT_FALSE(estimate_accumulation({0.1, -1.0, 0.0, 0.5, 0.0}));
  EXPECT_FALSE(estimate_accumulation({0.1, 1.0, 0.0, 1.0, 0.0}));
}

// Below the event loop's resolution the estimate is taken whatever its bound.
TEST(AccumulationEstimate, IsTakenWhenTheChatterIsUnresolvable) {
  const ChatterProbe probe{1e-7, 1.0, 100.0, 0.3, 0.0};
  EXPECT_FALSE(accept_accumulation(probe, {.time = 1e-30, .unresolved_apex = 1e-16, .gap_roundoff = 0.0}));
  EXPECT_TRUE(accept_accumulation(probe, {.time = 1e-30, .unresolved_apex = 1e-14, .gap_roundoff = 0.0}));
  // or when the next impact's round-off timing error ρ/u exceeds the bound
  EXPECT_TRUE(accept_accumulation(probe, {.time = 1e-30, .unresolved_apex = 0.0, .gap_roundoff = 1e-17}));
}

// --- whole runs ------------------------------------------------------------

RunOutput run_scene(const std::string& name, const std::vector<std::string>& assignments,
                    double t_end) {
  Scene scene = load_scene(name);
  for (const auto& assignment : assignments) apply_override(scene, assignment);
  RunRequest request;
  request.periods = 0.0;
  request.t_end = t_end;
  return run_of_scene(scene, request);
}

const EventRecord* first_accumulation(const RunOutput& output) {
  for (const auto& event : output.events)
    if (event.kind == EventKind::accumulation) return &event;
  return nullptr;
}

std::string setting(const char* key, double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%s=%.17g", key, value);
  return text;
}

// The ball dropped from 5 cm on a table at rest: impacts at
// t1 = √(2h/g), then flights 2 r^k v1 / g; accumulation at
// t1 + 2 r v1 / (g (1 − r)), v1 = √(2 g h). Every setting of the
// accumulation tolerance and the integrator's completes, and the error of
// the accumulation time stays within the tolerance the impacts are held to.
TEST(BouncingBallAccumulation, MatchesTheClosedFormAtEverySetting) {
  const double h = 0.05, g = 9.81, r = 0.8;
  const double v1 = std::sqrt(2.0 * g * h);
  const double t_acc = std::sqrt(2.0 * h / g) + 2.0 * r * v1 / (g * (1.0 - r));
  for (const char* method : {"dopri5", "exact"}) {
    for (double accumulation_tol : {1e-2, 1e-6, 1e-9, 1e-12, 1e-14}) {
      for (double rtol : {1e-6, 1e-10, 1e-14}) {
        SCOPED_TRACE(std::string(method) + " " + setting("accumulation_tol", accumulation_tol) +
                     " " + setting("rtol", rtol));
        const RunOutput output = run_scene(
            "bouncing_ball",
            {"A=0", "r=0.8", "initial.y=0.05", "initial.y_dot=0",
             std::string("integrator.method=") + method, setting("integrator.rtol", rtol),
             setting("accumulation_tol", accumulation_tol)},
            2.0);
        ASSERT_EQ(output.termination, impactlab::Termination::completed);
        const EventRecord* acc = first_accumulation(output);
        ASSERT_NE(acc, nullptr);
        // a fixed table: the constant-acceleration sum is exact, the error is
        // the impacts' own; exact flows are right to round-off
        const double impact_tolerance = std::string(method) == "exact" ? 1e-13 : 1e-3 * rtol + 1e-12;
        EXPECT_NEAR(acc->t, t_acc, impact_tolerance);
        EXPECT_GE(acc->accumulation_error, 0.0);
      }
    }
  }
}

// --- jin2003, V0 = 4.163 m/s: the independent long-double reference -------

struct PendulumReference {
  long double m = 0.5L, l = 0.7L, b = 0.05L, d = 0.01L, g = 9.81L, V0 = 4.163L, omega = 7.0L,
              e_n = 0.3L;
};

// θ̈ of the free pendulum with the pivot moving at V0 sin ωt (y down)
long double angular_acceleration(const PendulumReference& p, long double t, long double theta,
                                 long double theta_dot) {
  const long double g_e = p.g - p.V0 * p.omega * std::cos(p.omega * t);
  return -(p.d * theta_dot + p.m * p.l * g_e * std::sin(theta)) / (p.m * p.l * p.l);
}

void rk4_step(const PendulumReference& p, long double t, long double theta, long double rate,
              long double h, long double& theta1, long double& rate1) {
  const long double k1x = rate, k1v = angular_acceleration(p, t, theta, rate);
  const long double k2x = rate + 0.5L * h * k1v,
                    k2v = angular_acceleration(p, t + 0.5L * h, theta + 0.5L * h * k1x, k2x);
  const long double k3x = rate + 0.5L * h * k2v,
                    k3v = angular_acceleration(p, t + 0.5L * h, theta + 0.5L * h * k2x, k3x);
  const long double k4x = rate + h * k3v,
                    k4v = angular_acceleration(p, t + h, theta + h * k3x, k4x);
  theta1 = theta + h / 6.0L * (k1x + 2.0L * k2x + 2.0L * k3x + k4x);
  rate1 = rate + h / 6.0L * (k1v + 2.0L * k2v + 2.0L * k3v + k4v);
}

// The time of the first accumulation from θ = 0, θ̇ = 0.1 rad/s at t = 0.
long double reference_first_accumulation(const PendulumReference& p) {
  const long double theta0 = std::asin(p.b / p.l);
  const long double base_step = 1e-5L;
  long double t = 0.0L, theta = 0.0L, rate = 0.1L, step = base_step;
  while (t < 10.0L) {
    long double theta1, rate1;
    rk4_step(p, t, theta, rate, step, theta1, rate1);
    if (std::fabs(theta1) < theta0) {
      t += step;
      theta = theta1;
      rate = rate1;
      continue;
    }
    // a wall reached inside the step: bisect on the step length
    const long double wall = theta1 > 0.0L ? 1.0L : -1.0L;
    long double lo = 0.0L, hi = step;
    for (int k = 0; k < 90; ++k) {
      const long double mid = 0.5L * (lo + hi);
      rk4_step(p, t, theta, rate, mid, theta1, rate1);
      (wall * theta1 >= theta0 ? hi : lo) = mid;
    }
    rk4_step(p, t, theta, rate, hi, theta1, rate1);
    t += hi;
    theta = wall * theta0;
    rate = -p.e_n * rate1;
    // the acceleration towards the wall at rest on it (rad/s²), and the
    // constant-acceleration flight time
    const long double g_e = p.g - p.V0 * p.omega * std::cos(p.omega * t);
    const long double towards = -g_e * std::sin(theta0) / p.l;
    const long double u = std::fabs(rate);
    if (towards > 0.0L) {
      const long double remaining = 2.0L * u / (towards * (1.0L - p.e_n));
      if (remaining < 1e-7L) return t + remaining;
      step = std::min(base_step, 2.0L * u / towards / 64.0L);
    } else {
      step = base_step;
    }
  }
  return NAN;
}

class Jin2003Accumulation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    reference_ = static_cast<double>(reference_first_accumulation(PendulumReference{}));
  }
  static double reference_;
};
double Jin2003Accumulation::reference_ = NAN;

TEST_F(Jin2003Accumulation, DefaultSettingsAreWithinANanosecondOfTheReference) {
  ASSERT_TRUE(std::isfinite(reference_));
  const RunOutput output = run_scene("jin2003", {"V0=4.163"}, reference_ + 0.5);
  ASSERT_EQ(output.termination, impactlab::Termination::completed);
  const EventRecord* acc = first_accumulation(output);
  ASSERT_NE(acc, nullptr);
  EXPECT_NEAR(acc->t, reference_, 1e-9);
  // the bound the run reports: rtol / ω, or where the last impacts' round-off
  // limits the chatter (as here, 10 impacts), the estimate's bound plus the
  // round-off floor 2ρ/(u (1 − r)²) of those impacts: below 1e-9 itself
  EXPECT_LE(acc->accumulation_error, 1e-9);
}

// Accumulation tolerance 1e-2 .. 1e-14 and integrator rtol 1e-6 .. 1e-14:
// every run completes, with the contact phase entered, and the error of the
// accumulation time falls as the tolerances fall.
TEST_F(Jin2003Accumulation, EverySettingCompletesAndTheErrorFallsWithTheTolerances) {
  ASSERT_TRUE(std::isfinite(reference_));
  const std::vector<double> accumulation_tols = {1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 1e-14};
  const std::vector<double> rtols = {1e-6, 1e-8, 1e-10, 1e-12, 1e-14};
  std::vector<std::vector<double>> error(rtols.size());
  for (std::size_t i = 0; i < rtols.size(); ++i) {
    for (double accumulation_tol : accumulation_tols) {
      SCOPED_TRACE(setting("rtol", rtols[i]) + " " + setting("accumulation_tol", accumulation_tol));
      const RunOutput output =
          run_scene("jin2003",
                    {"V0=4.163", setting("integrator.rtol", rtols[i]),
                     setting("accumulation_tol", accumulation_tol)},
                    reference_ + 0.5);
      ASSERT_EQ(output.termination, impactlab::Termination::completed);
      const EventRecord* acc = first_accumulation(output);
      ASSERT_NE(acc, nullptr);
      error[i].push_back(std::fabs(acc->t - reference_));
      // the reported bound holds wherever the integrator is not the limit
      if (rtols[i] <= 1e-12) {
        EXPECT_LE(error[i].back(), acc->accumulation_error + 1e-10);
      }
    }
  }
  // falls with the accumulation tolerance at tight rtol, and with rtol at
  // tight accumulation tolerance (up to the impacts' own error, 1e-10 s)
  const std::size_t tight_rtol = 3;  // 1e-12
  for (std::size_t j = 1; j < accumulation_tols.size(); ++j)
    EXPECT_LE(error[tight_rtol][j], error[tight_rtol][j - 1] + 1e-10) << "accumulation_tol " << j;
  for (std::size_t i = 1; i < rtols.size(); ++i)
    EXPECT_LE(error[i].back(), error[i - 1].back() + 1e-10) << "rtol " << i;
  EXPECT_LT(error[tight_rtol].back(), 1e-9);
  EXPECT_LT(error.back().back(), 1e-9);
}


// Model P with e_t = −1 is Model N impact for impact (docs/model-card.md): its
// chatter at V0 = 4.163 m/s reaches the same accumulation point, against the
// same reference, at every setting of both tolerances.
TEST_F(Jin2003Accumulation, ModelPAtTangentialRestitutionMinusOneMatchesTheReference) {
  ASSERT_TRUE(std::isfinite(reference_));
  for (double rtol : {1e-8, 1e-12, 1e-14}) {
    for (double accumulation_tol : {1e-2, 1e-9, 1e-14}) {
      SCOPED_TRACE(setting("rtol", rtol) + " " + setting("accumulation_tol", accumulation_tol));
      const RunOutput output =
          run_scene("jin2003",
                    {"model=paper", "e_t=-1", "V0=4.163", setting("integrator.rtol", rtol),
                     setting("accumulation_tol", accumulation_tol)},
                    reference_ + 0.5);
      ASSERT_EQ(output.termination, impactlab::Termination::completed);
      const EventRecord* acc = first_accumulation(output);
      ASSERT_NE(acc, nullptr);
      if (rtol <= 1e-12) {
        EXPECT_LE(std::fabs(acc->t - reference_), acc->accumulation_error + 1e-10);
      }
    }
  }
}

// The rigid-body model on the same chatter (rod and ball, Newton–Coulomb
// impulses): no independent reference here, so the promise checked is the
// issue's: every setting completes with the accumulation taken, and the
// time of each agrees with the tightest setting's within the two reported
// bounds (plus the impacts' own error, 1e-10 s at rtol 1e-12).
TEST(RigidPendulumAccumulation, EverySettingCompletesWithinItsReportedBound) {
  const auto accumulation_at = [](double rtol, double accumulation_tol) {
    const RunOutput output = run_scene(
        "jin2003",
        {"model=rigid", "V0=4.163", setting("integrator.rtol", rtol),
         setting("accumulation_tol", accumulation_tol)},
        1.6);
    EXPECT_EQ(output.termination, impactlab::Termination::completed);
    const EventRecord* acc = first_accumulation(output);
    EXPECT_NE(acc, nullptr);
    return acc ? std::pair<double, double>{acc->t, acc->accumulation_error}
               : std::pair<double, double>{NAN, NAN};
  };
  const auto [t_tight, bound_tight] = accumulation_at(1e-14, 1e-14);
  ASSERT_TRUE(std::isfinite(t_tight));
  for (double rtol : {1e-6, 1e-10, 1e-12}) {
    for (double accumulation_tol : {1e-2, 1e-6, 1e-9, 1e-12}) {
      SCOPED_TRACE(setting("rtol", rtol) + " " + setting("accumulation_tol", accumulation_tol));
      const auto [t, bound] = accumulation_at(rtol, accumulation_tol);
      ASSERT_TRUE(std::isfinite(t));
      if (rtol >= 1e-12) { EXPECT_LE(std::fabs(t - t_tight), bound + bound_tight + 1e-10); }
    }
  }
}

// --- the linear impact oscillator: closed-form flights in long double ------
//
// x'' + 2ζx' + x = A cos ωt, stop at x = σ, restitution r, from rest at
// x = 0, t = 0 (ω = 0.3, σ = 0.1: the chatter ends in sticking near t = 22).

struct LinearImpactReference {
  long double zeta = 0.05L, A = 1.0L, omega = 0.3L, sigma = 0.1L, r = 0.8L;
};

// The exact flow over τ from (x, v) at time t.
void linear_impact_flow(const LinearImpactReference& p, long double t, long double x,
                        long double v, long double tau, long double& x1, long double& v1) {
  const long double w = p.omega;
  const long double D = (1.0L - w * w) * (1.0L - w * w) + 4.0L * p.zeta * p.zeta * w * w;
  const long double P = p.A * (1.0L - w * w) / D, Q = p.A * 2.0L * p.zeta * w / D;
  const auto xp = [&](long double s) { return P * std::cos(w * s) + Q * std::sin(w * s); };
  const auto vp = [&](long double s) { return w * (Q * std::cos(w * s) - P * std::sin(w * s)); };
  const long double wd = std::sqrt(1.0L - p.zeta * p.zeta);
  const long double c1 = x - xp(t), c2 = (v - vp(t) + p.zeta * c1) / wd;
  const long double decay = std::exp(-p.zeta * tau), c = std::cos(wd * tau), s = std::sin(wd * tau);
  x1 = xp(t + tau) + decay * (c1 * c + c2 * s);
  v1 = vp(t + tau) + decay * (-p.zeta * (c1 * c + c2 * s) + wd * (-c1 * s + c2 * c));
}

// The time of the first accumulation: the flow scanned in steps (1 ms, or a
// 64th of the flight in the chatter), each impact bisected to long-double
// round-off, closed by the constant-acceleration tail once the remaining
// time is below 1e-7 (its error then below 1e-13).
long double reference_linear_impact_accumulation(const LinearImpactReference& p) {
  const long double base_step = 1e-3L;
  long double t = 0.0L, x = 0.0L, v = 0.0L, step = base_step;
  while (t < 200.0L) {
    long double x1, v1;
    linear_impact_flow(p, t, x, v, step, x1, v1);
    if (x1 < p.sigma) {
      t += step;
      x = x1;
      v = v1;
      continue;
    }
    long double lo = 0.0L, hi = step;
    for (int k = 0; k < 90; ++k) {
      const long double mid = 0.5L * (lo + hi);
      linear_impact_flow(p, t, x, v, mid, x1, v1);
      (x1 >= p.sigma ? hi : lo) = mid;
    }
    linear_impact_flow(p, t, x, v, hi, x1, v1);
    t += hi;
    x = p.sigma;
    v = -p.r * v1;
    // the acceleration towards the stop at rest on it
    const long double towards = p.A * std::cos(p.omega * t) - p.sigma;
    const long double u = std::fabs(v);
    if (towards > 0.0L) {
      const long double remaining = 2.0L * u / (towards * (1.0L - p.r));
      if (remaining < 1e-7L) return t + remaining;
      step = std::min(base_step, 2.0L * u / towards / 64.0L);
    } else {
      step = base_step;
    }
  }
  return NAN;
}

// Default settings within 1e-9 of the reference; every accumulation
// tolerance from 1e-2 to 1e-14 completes, and the error stays within the
// reported bound and falls with the tolerance (the flow is exact, so rtol
// plays no part).
TEST(LinearImpactAccumulation, MatchesTheClosedFormReferenceAtEveryTolerance) {
  const double reference =
      static_cast<double>(reference_linear_impact_accumulation(LinearImpactReference{}));
  ASSERT_TRUE(std::isfinite(reference));
  const std::vector<std::string> scene = {"omega=0.3", "sigma=0.1", "zeta=0.05", "A=1", "r=0.8"};
  const auto accumulation_with = [&](std::vector<std::string> assignments) {
    assignments.insert(assignments.begin(), scene.begin(), scene.end());
    const RunOutput output = run_scene("linear_impact", assignments, reference + 1.0);
    EXPECT_EQ(output.termination, impactlab::Termination::completed);
    const EventRecord* acc = first_accumulation(output);
    EXPECT_NE(acc, nullptr);
    return acc ? *acc : EventRecord{};
  };
  const EventRecord by_default = accumulation_with({});
  EXPECT_NEAR(by_default.t, reference, 1e-9);
  double previous_error = INFINITY;
  for (double accumulation_tol : {1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 1e-14}) {
    SCOPED_TRACE(setting("accumulation_tol", accumulation_tol));
    const EventRecord acc = accumulation_with({setting("accumulation_tol", accumulation_tol)});
    const double error = std::fabs(acc.t - reference);
    EXPECT_LE(error, acc.accumulation_error + 1e-12);
    EXPECT_LE(error, previous_error + 1e-12);
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-9);
}

// A chatter where the wall stops attracting: jin2003 at ω = 5.606 rad/s,
// V0 = 1.955 m/s, from the state the 100 × 100 map brings to that point,
// chatters on the right wall at t ≈ 64 s while g_e = g − V0 ω cos ωt passes
// through zero, so the hops neither shrink fast nor accumulate. After the
// eighth rebound (1.9e-6 rad/s) the next hop, its crossing and the state's
// way back out past the wall all fall inside one scan interval of rkf78's
// step: the right sample is past zero and rising again. The scan took that
// for a violation and stopped with no_progress; it now halves the interval
// towards the rebound until the hop's falling flank is sampled
// (integrate/event_location.hpp). Every stepper runs through.
TEST(Jin2003Chatter, WhereTheWallStopsAttractingRunsThrough) {
  for (const std::string method : {"taylor", "rkf78", "rk8pd", "dopri5"}) {
    const RunOutput output = run_scene(
        "jin2003",
        {"omega=5.606060606060606", "V0=1.9545454545454546", "initial.theta=0.02533801725182166",
         "initial.theta_dot=-0.006388163122412664", "integrator.method=" + method},
        150.0 * 2.0 * std::numbers::pi / 5.606060606060606);  // 150 forcing periods (s)
    EXPECT_EQ(output.termination, impactlab::Termination::completed) << method << " stopped at t = " << output.t_final;
    EXPECT_GT(output.impacts, 50u) << method;
  }
}

}  // namespace
}  // namespace impactlab
