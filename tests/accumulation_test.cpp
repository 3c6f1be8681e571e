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
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "contact/accumulation.hpp"
#include "api/oscillator_registry.hpp"
#include "api/scene_loading.hpp"
#include "io/scene.hpp"

namespace impactlab {
namespace {

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

class AccumulationEstimate : public testing::TestWithParam<ModelCase> {};

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
    testing::Values(ModelCase{0.0, 0.02, 0.0, 0.01}, ModelCase{0.3, 0.02, 0.0, 0.007},
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
  return oscillator_entry(scene.oscillator).run(scene, request);
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
        ASSERT_EQ(output.termination, "completed");
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

class Jin2003Accumulation : public testing::Test {
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
  ASSERT_EQ(output.termination, "completed");
  const EventRecord* acc = first_accumulation(output);
  ASSERT_NE(acc, nullptr);
  EXPECT_NEAR(acc->t, reference_, 1e-9);
  // the bound the run reports: rtol / ω, or where the last impacts' round-off
  // limits the chatter (as here, 10 impacts), that bound, still far below 1e-9
  EXPECT_LE(acc->accumulation_error, 1e-11);
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
      ASSERT_EQ(output.termination, "completed");
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

}  // namespace
}  // namespace impactlab
