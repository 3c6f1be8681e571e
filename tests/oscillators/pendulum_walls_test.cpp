// Tests of the pendulum between two walls (Model N, docs/simulation.md) run through
// the event loop, against closed forms derived by hand:
// * the release time of a contact phase, g_e(t_r) = g − V0 ω cos ωt_r = 0;
// * the friction work of a contact phase, ∫ μ λ_N |V0 sin ωt| dt;
// * Newton's impact law and the normal impulse of each impact;
// * energy conservation at e_n = 1, d = 0, V0 = 0;
// * the Painlevé diagnostic (μ tan θ0 ≥ 1) at an impact and at a slip reversal;
// * the number of impacts the accumulation rule lets through before it jumps.
// Nothing here is compared with a value produced by running the code under
// test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/core/event_log.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/pendulum_walls/pendulum_walls.hpp>

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

using State = PendulumWalls::State;
using Mode = PendulumWalls::Mode;
constexpr double pi = std::numbers::pi;

// steppers with a numerical flow (the pendulum has no closed-form flow)
const std::vector<std::string> numerical_steppers = {"dopri5", "rkf78", "bulirsch_stoer", "rk8pd",
                                                     "taylor"};

// Jin, Hu & Bishop (2003): the parameter defaults, with the given V0
PendulumWallsParameters jin2003(double V0) {
  PendulumWallsParameters p;
  p.V0 = V0;
  return p;
}

// wall geometry by hand: sin θ0 = b / l, cos θ0 = √(1 − (b/l)²)
double sin_theta0(const PendulumWallsParameters& p) { return p.b / p.l; }
double cos_theta0(const PendulumWallsParameters& p) {
  return std::sqrt(1.0 - (p.b / p.l) * (p.b / p.l));
}
double sign_of(double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; }

struct PendulumRun {
  RunResult<State, Mode> result;
  EventLog log;
};

// One run of the pendulum from (t0, x0) in free flight to t_end.
template <class Observer = NoObserver>
PendulumRun run_pendulum(const PendulumWallsParameters& p, std::string_view method, const State& x0,
                         double t0, double t_end, double rtol, double atol,
                         Observer&& observer = Observer{}) {
  const PendulumWalls system(p);
  StepperSettings settings;
  settings.rtol = rtol;
  settings.atol = atol;
  settings.max_step = system.max_step();
  PendulumRun out;
  out.result = with_flow<PendulumWalls>(method, settings, [&](auto& stepper) {
    return simulate(system, stepper, x0, Mode::free, t0, t_end, LoopOptions{}, out.log,
                    std::forward<Observer>(observer));
  });
  return out;
}

// Samples a run on a uniform time grid (spacing in s) and records what must
// hold: the bob never beyond a wall; in every contact phase λ_N ≥ 0, the bob
// on the wall at rest, and a friction work that never decreases.
class ContactSampler {
 public:
  ContactSampler(const PendulumWalls& system, double spacing, double t0 = 0.0)
      : system_(&system), spacing_(spacing), t0_(t0) {}

  [[nodiscard]] double next_time() const { return t0_ + static_cast<double>(index_) * spacing_; }

  template <class S, class M>
  void observe(double t, const S& x, M mode) {
    ++index_;
    const PendulumWallsParameters& p = system_->parameters();
    max_penetration = std::max(max_penetration, p.l * std::fabs(std::sin(x[0])) - p.b);
    if (mode == Mode::free) {
      previous_contact_work = -INFINITY;
      return;
    }
    ++contact_samples;
    if (x[2] < previous_contact_work) ++work_decreases;
    previous_contact_work = x[2];
    const double slip_sign = sign_of(system_->pivot_velocity(t));
    const double lambda = system_->normal_force(t, slip_sign);
    if (lambda < min_normal_force) {
      min_normal_force = lambda;
      time_of_min = t;
    }
    const double wall = mode == Mode::contact_right ? 1.0 : -1.0;
    max_off_wall = std::max(max_off_wall, std::fabs(x[0] - wall * system_->wall_angle()));
    if (x[1] != 0.0) ++moving_in_contact;
  }

  std::size_t contact_samples = 0;
  std::size_t work_decreases = 0;      // in one contact phase
  std::size_t moving_in_contact = 0;   // samples with θ̇ ≠ 0
  double max_off_wall = 0.0;           // |θ ∓ θ0| in contact (rad)
  double max_penetration = -INFINITY;  // l |sin θ| − b (m)
  double min_normal_force = INFINITY;  // N
  double time_of_min = NAN;            // s

 private:
  const PendulumWalls* system_;
  double spacing_;  // s
  double t0_;       // s
  long index_ = 0;
  double previous_contact_work = -INFINITY;  // J
};

// How exactly a stepper keeps a state whose derivative is zero. A Runge–Kutta
// step and its dense output add h·Σ bᵢ·0 = 0: exact. Bulirsch–Stoer's
// extrapolation combines tableau entries as (1 + c)·x − c·x, which rounds:
// the resting state moves by a few ulps per step (1e-15 rad is ~70 ulps of θ0).
double resting_state_tolerance(std::string_view method) {
  return method == "bulirsch_stoer" ? 1e-15 : 0.0;
}

// Antiderivative of (V0 ω cos ωt − g) V0 sin ωt (m²/s³ integrated: m²/s²):
//     F(t) = V0² sin²(ωt) / 2 + g V0 cos(ωt) / ω
double friction_antiderivative(const PendulumWallsParameters& p, double t) {
  const double s = std::sin(p.omega * t);
  return 0.5 * p.V0 * p.V0 * s * s + p.g * p.V0 * std::cos(p.omega * t) / p.omega;
}

// Friction work (J) over [ta, tb] with slip sign s (constant on the interval):
//     ∫ μ λ_N |V0 sin ωt| dt,  λ_N = m (V0 ω cos ωt − g) sin θ0 / (cos θ0 − s μ sin θ0)
//     = μ m sin θ0 s / (cos θ0 − s μ sin θ0) · (F(tb) − F(ta))
double friction_work_closed_form(const PendulumWallsParameters& p, double ta, double tb, double s) {
  const double denominator = cos_theta0(p) - s * p.mu * sin_theta0(p);
  return p.mu * p.m * sin_theta0(p) * s / denominator *
         (friction_antiderivative(p, tb) - friction_antiderivative(p, ta));
}

// The last events of a log, for failure messages.
std::string last_events(const EventLog& log, std::size_t count = 4) {
  const std::vector<EventRecord>& records = log.records();
  std::string text = "last events:";
  const std::size_t first = records.size() > count ? records.size() - count : 0;
  for (std::size_t i = first; i < records.size(); ++i) {
    text.append(" ").append(to_string(records[i].kind)).append("@");
    text.append(std::to_string(records[i].t));
  }
  return text;
}

std::string stepper_test_name(const ::testing::TestParamInfo<std::string>& info) {
  return info.param;
}

// ---------------------------------------------------------------------------
// Contact phases of the paper's case V0 = 4.163 m/s, ω = 7 rad/s.

class PendulumWallsContact : public ::testing::TestWithParam<std::string> {};

TEST_P(PendulumWallsContact, Jin2003ContactPhasesMatchClosedForms) {
  const PendulumWallsParameters p = jin2003(4.163);
  const PendulumWalls system(p);
  const double period = 2.0 * pi / p.omega;
  const double t_end = 100.0 * period;
  // rk8pd's dense output re-takes a step (13 evaluations): sample it coarser
  const double spacing = GetParam() == "rk8pd" ? 1e-4 : 1e-5;  // s
  ContactSampler sampler(system, spacing);
  const PendulumRun run =
      run_pendulum(p, GetParam(), {0.0, 0.1, 0.0}, 0.0, t_end, 1e-10, 1e-12, sampler);

  EXPECT_EQ(run.result.termination, Termination::completed);
  EXPECT_EQ(run.result.t, t_end);
  EXPECT_GE(run.log.count(EventKind::accumulation), 1u);
  EXPECT_GE(run.log.count(EventKind::contact_start), 1u);
  EXPECT_GE(run.log.count(EventKind::contact_end), 1u);
  EXPECT_EQ(run.log.count(EventKind::painleve), 0u);

  // the sampled contact phases: λ_N ≥ 0, on the wall at rest, work nondecreasing
  EXPECT_GT(sampler.contact_samples, 100u);
  EXPECT_GE(sampler.min_normal_force, 0.0) << "at t = " << sampler.time_of_min;
  EXPECT_LE(sampler.max_off_wall, resting_state_tolerance(GetParam()));
  EXPECT_EQ(sampler.moving_in_contact, 0u);
  EXPECT_EQ(sampler.work_decreases, 0u);
  // never beyond a wall by more than the event locator's touching tolerance
  EXPECT_LE(sampler.max_penetration, LoopOptions{}.location.grazing_tolerance);

  // the release root: g − V0 ω cos ωt = 0 ⇔ ωt = ±acos(g / (V0 ω)) + 2πk; a
  // falling λ_N ∝ −g_e means a rising g_e, cos ωt decreasing: the + branch
  const double release_phase = std::acos(p.g / (p.V0 * p.omega));  // rad
  const double theta0 = std::asin(p.b / p.l);
  double previous_work = 0.0;
  std::size_t phases = 0;
  bool in_contact = false;
  double segment_start = 0.0, slip_sign = 0.0, work_at_start = 0.0, work_closed_form = 0.0;
  int contact_wall = 0;
  for (const EventRecord& e : run.log.records()) {
    if (!std::isnan(e.friction_work)) {
      EXPECT_GE(e.friction_work, previous_work) << to_string(e.kind) << " at t = " << e.t;
      previous_work = e.friction_work;
    }
    switch (e.kind) {
      case EventKind::contact_start:
        ASSERT_FALSE(in_contact);
        in_contact = true;
        contact_wall = e.wall;
        EXPECT_EQ(e.q, e.wall * theta0);
        EXPECT_GT(e.normal_force, 0.0);
        EXPECT_EQ(e.qdot_before, 0.0);
        segment_start = e.t;
        slip_sign = e.tangential_velocity != 0.0 ? sign_of(e.tangential_velocity)
                                                 : sign_of(std::cos(p.omega * e.t));
        work_at_start = e.friction_work;
        work_closed_form = 0.0;
        break;
      case EventKind::slip_reversal:
        ASSERT_TRUE(in_contact);
        work_closed_form += friction_work_closed_form(p, segment_start, e.t, slip_sign);
        EXPECT_NEAR(e.friction_work - work_at_start, work_closed_form,
                    1e-8 * std::fabs(work_closed_form));
        // the pivot's velocity V0 sin ωt vanishes: ωt = πk
        EXPECT_NEAR(e.t, std::round(p.omega * e.t / pi) * pi / p.omega, 1e-9);
        segment_start = e.t;
        slip_sign = -slip_sign;
        break;
      case EventKind::contact_end: {
        ASSERT_TRUE(in_contact);
        in_contact = false;
        ++phases;
        EXPECT_EQ(e.wall, contact_wall);
        EXPECT_LE(std::fabs(e.q - e.wall * theta0), resting_state_tolerance(GetParam()));
        const double k = std::round((p.omega * e.t - release_phase) / (2.0 * pi));
        const double k_minus = std::round((p.omega * e.t + release_phase) / (2.0 * pi));
        const double t_plus = (release_phase + 2.0 * pi * k) / p.omega;
        const double t_minus = (-release_phase + 2.0 * pi * k_minus) / p.omega;
        EXPECT_LT(std::fabs(e.t - t_plus), std::fabs(e.t - t_minus))
            << "release on the wrong branch of g_e = 0 at t = " << e.t;
        EXPECT_NEAR(e.t, t_plus, 1e-9);
        work_closed_form += friction_work_closed_form(p, segment_start, e.t, slip_sign);
        EXPECT_GT(work_closed_form, 0.0);
        EXPECT_NEAR(e.friction_work - work_at_start, work_closed_form,
                    1e-8 * std::fabs(work_closed_form))
            << "contact phase ending at t = " << e.t;
        break;
      }
      default:
        break;
    }
  }
  EXPECT_GE(phases, 1u);
}

// Every impact of the chattering case and of the paper's periodic case obeys
// Newton's law exactly, with the hand formula for the normal impulse.
TEST_P(PendulumWallsContact, ImpactsObeyNewtonLawWithHandImpulse) {
  for (const double V0 : {1.5, 4.163}) {
    const PendulumWallsParameters p = jin2003(V0);
    const PendulumRun run =
        run_pendulum(p, GetParam(), {0.0, 0.1, 0.0}, 0.0, 100.0 * 2.0 * pi / p.omega, 1e-10, 1e-12);
    ASSERT_EQ(run.result.termination, Termination::completed);
    std::size_t impacts = 0;
    for (const EventRecord& e : run.log.records()) {
      if (e.kind != EventKind::impact) continue;
      ++impacts;
      SCOPED_TRACE("V0 = " + std::to_string(V0) + ", impact at t = " + std::to_string(e.t));
      // θ̇⁺ = −e_n θ̇⁻, exactly
      EXPECT_EQ(e.qdot_after, -p.e_n * e.qdot_before);
      // on the wall it hit, moving into it
      EXPECT_NEAR(p.l * std::sin(e.q), e.wall * p.b, 1e-12);
      EXPECT_GT(e.wall * e.qdot_before, 0.0);
      // γ_T = V0 sin ωt − l sin θ θ̇⁻
      const double gamma_t = p.V0 * std::sin(p.omega * e.t) - p.l * std::sin(e.q) * e.qdot_before;
      EXPECT_NEAR(e.tangential_velocity, gamma_t, 1e-14 * (p.V0 + 1.0));
      // P_N = (1 + e_n) m l |θ̇⁻| / (cos θ0 − s μ sin θ0), s = sgn γ_T
      const double s = sign_of(e.tangential_velocity);
      const double impulse = (1.0 + p.e_n) * p.m * p.l * std::fabs(e.qdot_before) /
                             (cos_theta0(p) - s * p.mu * sin_theta0(p));
      EXPECT_NEAR(e.normal_impulse, impulse, 1e-13 * impulse);
    }
    EXPECT_GT(impacts, 50u);
  }
}

// Chattering is jumped over, not crawled through. After an impact with
// restitution r the flights form (at nearly constant normal acceleration a) a
// geometric series, each separation speed r times the last, whose sum is
// T0 = 2u / (a (1 − r)). The rule of contact/accumulation.hpp takes
// T = T0 − (T0²/3)(ȧ/a + c/2) (c = d/(m l²), the damping rate) once its
// error bound E = T0³ (½ (|ȧ|/a + c/2)² + ¼ |ä|/a + ⅕ |κ|) (κ = g_e cos θ0 / l)
// is within the accepted time error; E shrinks by r³ per impact, so from the
// first impact of a sequence at most n = ceil(ln(tol / E_1) / (3 ln r)) more
// pass before the jump. The acceleration is not constant over the early,
// long flights, so allow twice 1 + n; crawling would take hundreds of
// impacts (or trip the Zeno guard).
class PendulumWallsChatter : public ::testing::TestWithParam<double> {};

TEST_P(PendulumWallsChatter, ImpactsBeforeAccumulationAreBounded) {
  PendulumWallsParameters p = jin2003(5.0);
  p.e_n = GetParam();
  const PendulumRun run =
      run_pendulum(p, "dopri5", {0.0, 0.1, 0.0}, 0.0, 100.0 * 2.0 * pi / p.omega, 1e-10, 1e-12);
  ASSERT_EQ(run.result.termination, Termination::completed);
  ASSERT_GE(run.log.count(EventKind::accumulation), 1u);

  const double c = p.d / (p.m * p.l * p.l);
  // the normal acceleration towards the wall at rest on it and its rates
  // (m/s², m/s³, m/s⁴), u = l cos θ0 |θ̇⁺|, and the rule's T and E
  struct Chatter {
    double u, a, a_rate, a_curvature, kappa;
  };
  auto chatter_after = [&](const EventRecord& impact) {
    const double wt = p.omega * impact.t;
    const double g_e = p.g - p.V0 * p.omega * std::cos(wt);
    const double normal = sin_theta0(p) * cos_theta0(p);
    return Chatter{p.l * cos_theta0(p) * std::fabs(impact.qdot_after), -g_e * normal,
                   -p.V0 * p.omega * p.omega * std::sin(wt) * normal,
                   -p.V0 * std::pow(p.omega, 3) * std::cos(wt) * normal, g_e * cos_theta0(p) / p.l};
  };
  auto first_order_sum = [&](const Chatter& k) {
    const double t0 = 2.0 * k.u / (k.a * (1.0 - p.e_n));
    return t0 - t0 * t0 * (k.a_rate / k.a + 0.5 * c) / 3.0;
  };
  auto error_bound = [&](const Chatter& k) {
    const double t0 = 2.0 * k.u / (k.a * (1.0 - p.e_n));
    const double drift = std::fabs(k.a_rate) / k.a + 0.5 * c;
    return std::pow(t0, 3) * (0.5 * drift * drift + 0.25 * std::fabs(k.a_curvature) / k.a +
                              0.2 * std::fabs(k.kappa));
  };

  const std::vector<EventRecord>& records = run.log.records();
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].kind != EventKind::accumulation) continue;
    const EventRecord& accumulation = records[i];
    // the chatter sequence: the impacts on the same wall just before it
    std::size_t first = i;
    while (first > 0 && records[first - 1].kind == EventKind::impact &&
           records[first - 1].wall == accumulation.wall)
      --first;
    const std::size_t impacts = i - first;
    SCOPED_TRACE("accumulation at t = " + std::to_string(accumulation.t));
    ASSERT_GE(impacts, 1u);
    const Chatter first_chatter = chatter_after(records[first]);
    if (first_chatter.a > 0.0) {
      const double n = std::max(0.0, std::ceil(std::log(p.accumulation.time /
                                                        error_bound(first_chatter)) /
                                               (3.0 * std::log(p.e_n))));
      EXPECT_LE(static_cast<double>(impacts), 2.0 * (1.0 + n));
    }
    EXPECT_LE(impacts, 40u);
    // the jump is the first-order sum after the last impact, and its bound
    // is what the run reports and is within the tolerance (or the chatter
    // is below what the loop resolves)
    const EventRecord& last = records[i - 1];
    const Chatter k = chatter_after(last);
    ASSERT_GT(k.a, 0.0);
    const double remaining = first_order_sum(k);
    EXPECT_NEAR(accumulation.t - last.t, remaining, 1e-12 * (1.0 + remaining) + 1e-13 * last.t);
    EXPECT_NEAR(accumulation.accumulation_error, error_bound(k), 1e-9 * error_bound(k));
    const double apex = k.u * k.u / (2.0 * k.a);
    EXPECT_TRUE(error_bound(k) <= p.accumulation.time || apex <= p.accumulation.unresolved_apex ||
                error_bound(k) * k.u <= p.accumulation.gap_roundoff);
  }
}

INSTANTIATE_TEST_SUITE_P(Restitution, PendulumWallsChatter, ::testing::Values(0.1, 0.3, 0.5),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return "e_n_0" +
                                  std::to_string(static_cast<int>(std::lround(info.param * 10.0)));
                         });

// ---------------------------------------------------------------------------
// Energy: no damping, no forcing, elastic walls. The energy at each impact
// (from q and θ̇⁻) equals the initial energy.
//
// What is asserted and why: each free flight is a few controlled steps, and
// each impact restarts the integrator from the event state, which itself is
// a (partial) step or dense output of the controlled accuracy; so the flight
// and the impact together may add about one tolerance of relative error, and
// these errors add up over the run (a Runge–Kutta method is not symplectic,
// its energy error drifts). We therefore assert
//     |E_k − E_0| / E_0 ≤ k · rtol   for the k-th impact,
// i.e. ≤ 1e-6 after 10^4 impacts at rtol = 1e-10, and the same with the
// bound 100 times smaller at rtol = 1e-12. An event time off by δ puts the
// state off the wall by θ̇ δ before the reset snaps θ to ±θ0; that changes
// E/E_0 by about 2 δ / s here, so a location error of 1e-10 s per impact, or
// a lost or doubled impact, fails this test.
struct EnergyCase {
  std::string method;
  double rtol;
};

class PendulumWallsEnergy : public ::testing::TestWithParam<EnergyCase> {};

TEST_P(PendulumWallsEnergy, ElasticUnforcedEnergyIsConserved) {
  PendulumWallsParameters p = jin2003(0.0);
  p.d = 0.0;
  p.e_n = 1.0;
  const double theta_dot0 = 1.0;                                           // rad/s
  const double energy0 = 0.5 * p.m * p.l * p.l * theta_dot0 * theta_dot0;  // J, θ(0) = 0
  // time between impacts, by hand: the bob leaves the wall with the speed it
  // hit it, so each flight θ0 → −θ0 lasts the same time T_f; 10^4 impacts
  // need 10^4 T_f, with T_f below the time at the centre speed, 2 θ0 / θ̇(0)...
  const double theta0 = std::asin(p.b / p.l);
  // ...and above the time at the wall speed √(θ̇(0)² − 2 g (1 − cos θ0) / l)
  const double wall_speed =
      std::sqrt(theta_dot0 * theta_dot0 - 2.0 * p.g * (1.0 - std::cos(theta0)) / p.l);
  const double flight_upper = 2.0 * theta0 / wall_speed;
  const std::size_t target_impacts = 10000;
  const double t_end = static_cast<double>(target_impacts) * flight_upper;

  const EnergyCase c = GetParam();
  const PendulumRun run =
      run_pendulum(p, c.method, {0.0, theta_dot0, 0.0}, 0.0, t_end, c.rtol, 1e-2 * c.rtol);
  ASSERT_EQ(run.result.termination, Termination::completed);
  ASSERT_GE(run.log.count(EventKind::impact), target_impacts);
  EXPECT_EQ(run.log.count(EventKind::accumulation), 0u);
  EXPECT_EQ(run.log.count(EventKind::grazing), 0u);

  std::size_t k = 0;
  double worst = 0.0;
  int previous_wall = 0;
  for (const EventRecord& e : run.log.records()) {
    ASSERT_EQ(e.kind, EventKind::impact);
    ++k;
    // elastic, unforced: the walls alternate
    EXPECT_NE(e.wall, previous_wall) << "impact " << k;
    previous_wall = e.wall;
    EXPECT_EQ(e.qdot_after, -e.qdot_before);
    const double energy = 0.5 * p.m * p.l * p.l * e.qdot_before * e.qdot_before +
                          p.m * p.g * p.l * (1.0 - std::cos(e.q));
    const double relative_error = std::fabs(energy - energy0) / energy0;
    worst = std::max(worst, relative_error);
    ASSERT_LE(relative_error, static_cast<double>(k) * c.rtol) << "impact " << k << " t " << e.t;
  }
  RecordProperty("worst_relative_energy_error", std::to_string(worst));
}

INSTANTIATE_TEST_SUITE_P(
    Steppers, PendulumWallsEnergy,
    ::testing::Values(EnergyCase{"dopri5", 1e-10}, EnergyCase{"rkf78", 1e-10},
                    EnergyCase{"bulirsch_stoer", 1e-10}, EnergyCase{"rk8pd", 1e-10},
                    EnergyCase{"dopri5", 1e-12}, EnergyCase{"rkf78", 1e-12},
                    EnergyCase{"bulirsch_stoer", 1e-12}, EnergyCase{"rk8pd", 1e-12},
                    EnergyCase{"taylor", 1e-10}, EnergyCase{"taylor", 1e-12}),
    [](const ::testing::TestParamInfo<EnergyCase>& info) {
      return info.param.method + (info.param.rtol == 1e-10 ? "_rtol1e10" : "_rtol1e12");
    });

// ---------------------------------------------------------------------------
// Painlevé: with μ tan θ0 ≥ 1 the denominator cos θ0 − s μ sin θ0 is ≤ 0 for
// downward slip (s = +1, y down): the run stops with a typed diagnostic.

// μ = 15: μ tan θ0 = 15 · 0.05 / √(0.49 − 0.0025) ≈ 1.074 ≥ 1
// μ = 13: μ tan θ0 ≈ 0.931 < 1
constexpr double mu_painleve = 15.0;
constexpr double mu_consistent = 13.0;

TEST_P(PendulumWallsContact, PainleveAtImpactWithDownwardSlipStopsTheRun) {
  PendulumWallsParameters p = jin2003(1.5);
  p.mu = mu_painleve;
  ASSERT_GE(p.mu * sin_theta0(p) / cos_theta0(p), 1.0);
  const double t_end = 100.0 * 2.0 * pi / p.omega;
  const PendulumRun run = run_pendulum(p, GetParam(), {0.0, 0.1, 0.0}, 0.0, t_end, 1e-10, 1e-12);

  ASSERT_EQ(run.result.termination, Termination::stopped_by_model);
  ASSERT_FALSE(run.log.records().empty());
  EXPECT_EQ(run.log.count(EventKind::painleve), 1u);
  const EventRecord& painleve = run.log.records().back();
  ASSERT_EQ(painleve.kind, EventKind::painleve);
  // every earlier impact slipped upwards (else the run would have stopped there)
  for (const EventRecord& e : run.log.records())
    if (e.kind == EventKind::impact) {
      EXPECT_LT(e.tangential_velocity, 0.0) << "t = " << e.t;
    }
  // the diagnostic's time and state are where the run stopped
  EXPECT_LT(painleve.t, t_end);
  EXPECT_EQ(run.result.t, painleve.t);
  EXPECT_EQ(run.result.state[0], painleve.q);
  EXPECT_EQ(run.result.state[1], painleve.qdot_before);
  // on a wall, moving into it, slipping downwards
  ASSERT_NE(painleve.wall, 0);
  EXPECT_NEAR(p.l * std::sin(painleve.q), painleve.wall * p.b, 1e-12);
  EXPECT_GT(painleve.wall * painleve.qdot_before, 0.0);
  const double gamma_t =
      p.V0 * std::sin(p.omega * painleve.t) - p.l * std::sin(painleve.q) * painleve.qdot_before;
  EXPECT_GT(gamma_t, 0.0);
  EXPECT_NEAR(painleve.tangential_velocity, gamma_t, 1e-14 * (p.V0 + 1.0));
  EXPECT_LE(cos_theta0(p) - p.mu * sin_theta0(p), 0.0);
}

// A contact phase that starts while the pivot moves up (s = −1) and lasts
// past ωt = 2πk, where the slip turns downward (s = +1): the slip reversal is
// at t = 2πk / ω exactly; with μ tan θ0 ≥ 1 the run stops there. (Regression:
// λ_N, computed with the new slip sign, jumps from positive to negative at
// that instant, and must not be read as a release where λ_N reaches zero.)
// Set-up (e_n = 0, so the first impact on an attracting wall accumulates at
// once): V0 = 4.163 m/s, start at ωt0 = 2π − 1 (g_e < 0 there:
// cos 1 = 0.540 > g / (V0 ω) = 0.337) just off the right wall and moving
// towards it; run to ωt = 4π.
PendulumWallsParameters contact_across_reversal(double mu) {
  PendulumWallsParameters p = jin2003(4.163);
  p.mu = mu;
  p.e_n = 0.0;
  return p;
}

PendulumRun run_contact_across_reversal(const PendulumWallsParameters& p, std::string_view method) {
  const double theta0 = std::asin(p.b / p.l);
  const double t0 = (2.0 * pi - 1.0) / p.omega;
  return run_pendulum(p, method, {theta0 - 1e-3, 0.05, 0.0}, t0, 4.0 * pi / p.omega, 1e-10, 1e-12);
}

TEST_P(PendulumWallsContact, PainleveAtSlipReversalInContactStopsTheRun) {
  const PendulumWallsParameters p = contact_across_reversal(mu_painleve);
  const PendulumRun run = run_contact_across_reversal(p, GetParam());
  ASSERT_EQ(run.result.termination, Termination::stopped_by_model) << last_events(run.log);
  ASSERT_EQ(run.log.count(EventKind::contact_start), 1u);
  EXPECT_EQ(run.log.count(EventKind::slip_reversal), 0u);
  EXPECT_EQ(run.log.count(EventKind::contact_end), 0u);
  const EventRecord& painleve = run.log.records().back();
  ASSERT_EQ(painleve.kind, EventKind::painleve);
  EXPECT_EQ(painleve.wall, 1);
  // where the pivot's velocity V0 sin ωt turns positive: t = 2π / ω
  EXPECT_NEAR(painleve.t, 2.0 * pi / p.omega, 1e-12);
  EXPECT_EQ(run.result.t, painleve.t);
  // resting on the right wall
  const double theta0 = std::asin(p.b / p.l);
  EXPECT_LE(std::fabs(painleve.q - theta0), resting_state_tolerance(GetParam()));
  EXPECT_EQ(painleve.qdot_before, 0.0);
  EXPECT_EQ(run.result.state[0], painleve.q);
  EXPECT_EQ(run.result.state[1], 0.0);
  EXPECT_EQ(run.result.mode, Mode::contact_right);
}

TEST_P(PendulumWallsContact, NoPainleveBelowThreshold) {
  PendulumWallsParameters p = jin2003(1.5);
  p.mu = mu_consistent;
  ASSERT_LT(p.mu * sin_theta0(p) / cos_theta0(p), 1.0);
  const double t_end = 100.0 * 2.0 * pi / p.omega;
  const PendulumRun free_run =
      run_pendulum(p, GetParam(), {0.0, 0.1, 0.0}, 0.0, t_end, 1e-10, 1e-12);
  EXPECT_EQ(free_run.result.termination, Termination::completed);
  EXPECT_EQ(free_run.log.count(EventKind::painleve), 0u);
  // some impacts slip downwards and are consistent
  std::size_t downward = 0;
  for (const EventRecord& e : free_run.log.records())
    if (e.kind == EventKind::impact && e.tangential_velocity > 0.0) ++downward;
  EXPECT_GT(downward, 0u);

  // the contact across the slip reversal continues, with the reversal at 2π/ω
  // and λ_N there from the s = +1 formula, and releases where g_e = 0
  const PendulumWallsParameters pc = contact_across_reversal(mu_consistent);
  const PendulumRun contact_run = run_contact_across_reversal(pc, GetParam());
  EXPECT_EQ(contact_run.result.termination, Termination::completed);
  EXPECT_EQ(contact_run.log.count(EventKind::painleve), 0u);
  ASSERT_GE(contact_run.log.count(EventKind::slip_reversal), 1u);
  ASSERT_GE(contact_run.log.count(EventKind::contact_end), 1u);
  const double release_phase = std::acos(pc.g / (pc.V0 * pc.omega));
  bool reversal_seen = false, end_seen = false;
  for (const EventRecord& e : contact_run.log.records()) {
    if (e.kind == EventKind::slip_reversal && !reversal_seen) {
      reversal_seen = true;
      EXPECT_NEAR(e.t, 2.0 * pi / pc.omega, 1e-12);
      // λ_N = m (V0 ω − g) sin θ0 / (cos θ0 − μ sin θ0) at cos ωt = 1
      const double lambda = pc.m * (pc.V0 * pc.omega - pc.g) * sin_theta0(pc) /
                            (cos_theta0(pc) - pc.mu * sin_theta0(pc));
      EXPECT_NEAR(e.normal_force, lambda, 1e-12 * lambda);
    }
    if (e.kind == EventKind::contact_end && !end_seen) {
      end_seen = true;
      EXPECT_TRUE(reversal_seen);
      EXPECT_NEAR(e.t, (2.0 * pi + release_phase) / pc.omega, 1e-9);
    }
  }
}

// Resting on a wall that attracts (g_e < 0 at ωt0 = 2π, V0 ω > g): the
// bob is pushed into the wall and must stay on it, not pass through it.
// (Regression: a gap witness that starts at zero with zero rate was never
// armed, so the bob went through the wall without an event.)
TEST_P(PendulumWallsContact, RestingOnAttractingWallIsNotPenetrated) {
  const PendulumWallsParameters p = jin2003(4.163);
  const PendulumWalls system(p);
  const double t0 = 2.0 * pi / p.omega;
  const double theta0 = std::asin(p.b / p.l);
  ASSERT_LT(p.g - p.V0 * p.omega, 0.0);
  ContactSampler sampler(system, 1e-4, t0);
  const PendulumRun run =
      run_pendulum(p, GetParam(), {theta0, 0.0, 0.0}, t0, t0 + 0.5, 1e-10, 1e-12, sampler);
  EXPECT_EQ(run.result.termination, Termination::completed);
  EXPECT_LE(sampler.max_penetration, LoopOptions{}.location.grazing_tolerance)
      << last_events(run.log);
}

INSTANTIATE_TEST_SUITE_P(Steppers, PendulumWallsContact, ::testing::ValuesIn(numerical_steppers),
                         stepper_test_name);

// ---------------------------------------------------------------------------
// The pendulum has no closed-form flow: method = "exact" is refused.
TEST(PendulumWalls, ExactMethodIsRejected) {
  const PendulumWalls system(jin2003(1.5));
  StepperSettings settings;
  settings.max_step = system.max_step();
  try {
    with_stepper<PendulumWalls>("exact", settings, [](auto&) { return 0; });
    FAIL() << "method = exact was accepted";
  } catch (const std::invalid_argument& refused) {
    EXPECT_EQ(std::string(refused.what()).rfind("integrator.method = exact: ", 0), 0u)
        << refused.what();
  }
}

}  // namespace
}  // namespace impactlab
