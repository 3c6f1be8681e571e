// The two oscillators that ship only as scene files
// (oscillators/model_file/examples/), checked against results that do not
// come from the toolkit (docs/models.md states each one):
// * duffing_stop.toml with β = 0 is the linear impact oscillator: the built-in
//   C++ oscillator's events (impacts; chatter, sticking and release) to 1e-12;
// * duffing_stop.toml far from its stop at small forcing: the steady state's
//   fundamental against the harmonic-balance amplitude equation
//   a²[(1 − ω² + ¾βa²)² + (2ζω)²] = F² (to the size of the neglected third
//   harmonic's feedback), and the whole waveform against a harmonic balance
//   with the odd harmonics 1..9 solved here by Newton (to 1e-9 of a);
// * impact_damper.toml: momentum conserved at every impact (and kinetic
//   energy at r = 1), and the attractor at ω = 1.5 is the closed-form
//   symmetric orbit with two impacts per forcing period (Masri & Caughey
//   1966), derived for this model in docs/models.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/odeint_dopri5.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>

#include "support/model_parameters.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

constexpr double two_pi = 2.0 * std::numbers::pi;
const std::string examples = std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/";

std::shared_ptr<const CompiledModel> compiled(const std::string& file) {
  CompileOptions options;
  options.cache_directory = ::testing::TempDir() + "impactlab_model_examples_cache";
  return compile_model(read_model_file(examples + file), options);
}

using impactlab::testing::model_parameter_values;

StepperSettings settings_for(double max_step) {
  StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = max_step;
  return settings;
}

LoopOptions loop_options_for(const StepperSettings& settings) {
  LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  return options;
}

template <class System, class Observer = NoObserver>
RunResult<typename System::State, typename System::Mode> run(const System& system,
                                                             typename System::State x0,
                                                             double t0, double t_end,
                                                             EventLog& log,
                                                             Observer&& observer = Observer{}) {
  const StepperSettings settings = settings_for(system.max_step());
  // one stepper, compiled for this test's own systems (an ImpactRecorder is
  // not among the library's flows)
  OdeintDopri5<typename System::State> stepper(settings);
  return simulate(system, stepper, x0, typename System::Mode{}, t0, t_end,
                  loop_options_for(settings), log, observer);
}

// --- Duffing against a stop ---

// β = 0: the built-in linear impact oscillator, event by event.
TEST(DuffingStop, WithoutTheCubicTermItIsTheLinearImpactOscillator) {
  const auto model = compiled("duffing_stop.toml");
  struct Case {
    double sigma, r, omega, x0, periods;
    bool chatter;
  };
  // a period-1 impacting orbit; a low stop with soft impacts (chatter, rest, release)
  for (const Case c : {Case{0.2, 0.8, 2.0, 0.0, 60, false}, Case{0.0, 0.5, 0.5, -0.5, 20, true}}) {
    LinearImpactParameters p;
    p.sigma = c.sigma;
    p.r = c.r;
    p.omega = c.omega;
    const LinearImpact built_in{p};
    const ModelSystem<2> duffing(
        model, model_parameter_values(*model, {{"beta", 0.0}, {"F", p.A}, {"zeta", p.zeta}, {"sigma", c.sigma},
                               {"r", c.r}, {"omega", c.omega}}));
    EXPECT_DOUBLE_EQ(duffing.max_step(), built_in.max_step());
    const double t_end = c.periods * two_pi / c.omega;
    EventLog expected_log, actual_log;
    const StepperSettings settings = settings_for(built_in.max_step());
    const auto done = with_flow<LinearImpact>("dopri5", settings, [&](auto& stepper) {
      return simulate(built_in, stepper, {c.x0, 0.0}, LinearImpact::Mode::free, 0.0, t_end,
                      loop_options_for(settings), expected_log);
    });
    ASSERT_EQ(done.termination, Termination::completed);
    ASSERT_EQ(run(duffing, {c.x0, 0.0}, 0.0, t_end, actual_log).termination, Termination::completed);
    const auto& expected = expected_log.records();
    const auto& actual = actual_log.records();
    ASSERT_EQ(expected.size(), actual.size());
    ASSERT_GT(expected.size(), 50u);
    std::size_t accumulations = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      ASSERT_EQ(expected[i].kind, actual[i].kind) << i;
      EXPECT_NEAR(expected[i].t, actual[i].t, 1e-12) << i;
      EXPECT_NEAR(expected[i].qdot_after, actual[i].qdot_after, 1e-9) << i;
      accumulations += expected[i].kind == EventKind::accumulation;
    }
    EXPECT_EQ(accumulations > 5, c.chatter);
  }
}

// x(θ) = Σ over odd n ≤ 9 of a_n cos nθ + b_n sin nθ, θ = ωt, solving
// ω²x'' + 2ζωx' + x + βx³ = F cos θ in those harmonics (Galerkin: the
// residual's projections on them vanish), by Newton from the one-harmonic
// linear response. The neglected 11th harmonic is of relative size
// (βa²)^5 or so: below 1e-15 at the amplitudes used here.
struct HarmonicBalance {
  static constexpr int harmonics = 5;  // n = 1, 3, 5, 7, 9
  static constexpr int samples = 128;  // collocation points over one period
  double zeta, beta, force, omega;
  Eigen::Matrix<double, 2 * harmonics, 1> c = Eigen::Matrix<double, 2 * harmonics, 1>::Zero();

  [[nodiscard]] static int order(int j) { return 2 * j + 1; }
  [[nodiscard]] std::array<double, 3> at(double theta) const {  // x, dx/dθ, d²x/dθ²
    std::array<double, 3> x{};
    for (int j = 0; j < harmonics; ++j) {
      const double n = order(j), cs = std::cos(n * theta), sn = std::sin(n * theta);
      x[0] += c[2 * j] * cs + c[2 * j + 1] * sn;
      x[1] += n * (-c[2 * j] * sn + c[2 * j + 1] * cs);
      x[2] += -n * n * (c[2 * j] * cs + c[2 * j + 1] * sn);
    }
    return x;
  }
  [[nodiscard]] Eigen::Matrix<double, 2 * harmonics, 1> residual() const {
    Eigen::Matrix<double, 2 * harmonics, 1> r = Eigen::Matrix<double, 2 * harmonics, 1>::Zero();
    for (int k = 0; k < samples; ++k) {
      const double theta = two_pi * k / samples;
      const auto x = at(theta);
      const double e = omega * omega * x[2] + 2 * zeta * omega * x[1] + x[0] +
                       beta * x[0] * x[0] * x[0] - force * std::cos(theta);
      for (int j = 0; j < harmonics; ++j) {
        r[2 * j] += e * std::cos(order(j) * theta) / samples;
        r[2 * j + 1] += e * std::sin(order(j) * theta) / samples;
      }
    }
    return r;
  }
  void solve() {
    const double detuning = 1 - omega * omega, damping = 2 * zeta * omega;
    const double d = detuning * detuning + damping * damping;
    c[0] = force * detuning / d;
    c[1] = force * damping / d;
    for (int iteration = 0; iteration < 30; ++iteration) {
      const auto r = residual();
      if (r.norm() < 1e-17) break;
      Eigen::Matrix<double, 2 * harmonics, 2 * harmonics> jacobian;
      for (int i = 0; i < 2 * harmonics; ++i) {  // the residual is a cubic: central differences
        const double h = 1e-7;
        HarmonicBalance plus = *this, minus = *this;
        plus.c[i] += h;
        minus.c[i] -= h;
        jacobian.col(i) = (plus.residual() - minus.residual()) / (2 * h);
      }
      c -= jacobian.partialPivLu().solve(r);
    }
  }
};

// Samples x at equally spaced times (the simulator's observer).
struct Sampler {
  double t0, spacing;
  int count, next = 0;
  std::vector<double> x;
  [[nodiscard]] double next_time() const { return next < count ? t0 + next * spacing : INFINITY; }
  template <class State, class Mode>
  void observe(double, const State& v, Mode) {
    ++next;
    x.push_back(v[0]);
  }
};

// Far from the stop (σ = 10) and at small forcing the mass never reaches it:
// the steady state is the Duffing oscillator's. Its fundamental amplitude is
// the classical harmonic-balance amplitude to within the third harmonic's
// feedback on it, δa/a ≈ (3/16)β²a⁴/((9ω² − 1)|1 − ω² + ¾βa²|) (the cos θ part
// of 3βx²·b₃cos 3θ with b₃ = βa³/(4(9ω² − 1))): about 1e-7 here, against a
// harmonic balance that keeps harmonics 1..9 to 1e-9 (the integration's
// rtol 1e-10, and the transient e^{−ζt} < 1e-12 after 150 periods).
TEST(DuffingStop, FarFromTheStopTheSteadyStateIsTheHarmonicBalanceSolution) {
  const auto model = compiled("duffing_stop.toml");
  const double zeta = 0.05, beta = 0.5, force = 0.1, omega = 1.5;
  const ModelSystem<2> duffing(model, model_parameter_values(*model, {{"zeta", zeta}, {"beta", beta}, {"F", force},
                                                      {"omega", omega}, {"sigma", 10.0}}));
  const double period = two_pi / omega;
  HarmonicBalance balance{zeta, beta, force, omega};
  balance.solve();
  ASSERT_LT(balance.residual().norm(), 1e-15);

  EventLog log;
  constexpr int samples = 64;
  Sampler sampler{150 * period, period / samples, samples};
  const auto done = run(duffing, {0.0, 0.0}, 0.0, 151 * period, log, sampler);
  ASSERT_EQ(done.termination, Termination::completed);
  EXPECT_TRUE(log.records().empty());  // no impact
  ASSERT_EQ(sampler.x.size(), static_cast<std::size_t>(samples));

  // the waveform (θ = ωt; t = 150 T is θ ≡ 0)
  const double a1 = std::hypot(balance.c[0], balance.c[1]);
  double worst = 0.0;
  std::complex<double> fundamental = 0.0;
  for (int k = 0; k < samples; ++k) {
    const double theta = two_pi * k / samples;
    worst = std::max(worst, std::fabs(sampler.x[k] - balance.at(theta)[0]));
    fundamental += sampler.x[k] * std::exp(std::complex<double>(0.0, -theta)) * (2.0 / samples);
  }
  EXPECT_LT(worst, 1e-9 * a1);

  // the classical one-harmonic amplitude equation, solved for a by bisection
  // near the linear response (the only root: hardening, off resonance)
  auto amplitude_equation = [&](double a) {
    const double stiffness = 1 - omega * omega + 0.75 * beta * a * a;
    return a * a * (stiffness * stiffness + 4 * zeta * zeta * omega * omega) - force * force;
  };
  double low = 0.0, high = 2 * force;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (low + high);
    (amplitude_equation(mid) < 0 ? low : high) = mid;
  }
  const double a_hb = 0.5 * (low + high);
  const double measured = std::abs(fundamental);
  const double feedback = 3.0 / 16.0 * beta * beta * std::pow(a_hb, 4) /
                          ((9 * omega * omega - 1) *
                           std::fabs(1 - omega * omega + 0.75 * beta * a_hb * a_hb));
  EXPECT_LT(std::fabs(measured - a_hb), 2 * feedback * a_hb) << measured << " " << a_hb;
  EXPECT_GT(std::fabs(measured - a_hb), 0.5 * feedback * a_hb);  // it is that term
  EXPECT_NEAR(measured, a1, 1e-9 * a1);
}

// --- the impact damper ---

// Records the whole state before and after every impact of a system.
template <class Base>
class ImpactRecorder {
 public:
  using State = typename Base::State;
  using Mode = typename Base::Mode;
  static constexpr std::size_t max_witnesses = Base::max_witnesses;
  struct Impact {
    double t;
    std::size_t wall;
    State before, after;
  };

  ImpactRecorder(const Base& base, std::vector<Impact>& impacts) : base_(base), impacts_(&impacts) {}
  [[nodiscard]] double max_step() const { return base_.max_step(); }
  void rhs(Mode mode, const State& x, State& dxdt, double t) const { base_.rhs(mode, x, dxdt, t); }
  [[nodiscard]] std::size_t witness_count(Mode mode) const { return base_.witness_count(mode); }
  [[nodiscard]] TriggerDirection trigger_direction(Mode mode, std::size_t k) const {
    return base_.trigger_direction(mode, k);
  }
  [[nodiscard]] WitnessSample witness(Mode mode, std::size_t k, const State& x, double t) const {
    return base_.witness(mode, k, x, t);
  }
  Transition<State, Mode> on_event(Mode mode, std::size_t k, CrossingKind crossing, const State& x,
                                   double t, EventLog& log) const {
    auto transition = base_.on_event(mode, k, crossing, x, t, log);
    if (crossing == CrossingKind::crossing) impacts_->push_back({t, k, x, transition.state});
    return transition;
  }

 private:
  const Base& base_;
  std::vector<Impact>* impacts_;
};

// Each impact is an exchange of momentum between the primary (unit mass) and
// the ball (mass μ): x' + μy' is the same after it; at r = 1 so is the
// kinetic energy x'²/2 + μy'²/2.
TEST(ImpactDamper, MomentumIsConservedAtEveryImpactAndEnergyAtRestitutionOne) {
  const auto model = compiled("impact_damper.toml");
  for (const double r : {0.6, 1.0}) {
    const double mu = 0.1;
    const ModelSystem<4> damper(model, model_parameter_values(*model, {{"r", r}, {"mu", mu}, {"omega", 1.5}}));
    std::vector<ImpactRecorder<ModelSystem<4>>::Impact> impacts;
    const ImpactRecorder<ModelSystem<4>> recorder(damper, impacts);
    EventLog log;
    ASSERT_EQ(run(recorder, {0.0, 0.0, 0.0, 0.5}, 0.0, 50 * two_pi / 1.5, log).termination,
              Termination::completed);
    ASSERT_GT(impacts.size(), 50u);
    for (const auto& impact : impacts) {
      const auto& b = impact.before;
      const auto& a = impact.after;
      const double momentum = b[1] + mu * b[3];
      EXPECT_NEAR(a[1] + mu * a[3], momentum, 1e-14 * (std::fabs(b[1]) + mu * std::fabs(b[3])));
      const double energy = 0.5 * (b[1] * b[1] + mu * b[3] * b[3]);
      if (r == 1.0) {
        EXPECT_NEAR(0.5 * (a[1] * a[1] + mu * a[3] * a[3]), energy, 1e-14 * energy);
      }
      // Newton's law on the relative velocity, and positions unchanged
      EXPECT_NEAR(a[3] - a[1], -r * (b[3] - b[1]), 1e-14 * (std::fabs(b[1]) + std::fabs(b[3])));
      EXPECT_EQ(a[0], b[0]);
      EXPECT_EQ(a[2], b[2]);
    }
  }
}

// The symmetric orbit with two impacts per forcing period T, one on each wall
// half a period apart (docs/models.md derives it): with the impact at t₁ on
// the right wall, the ball's speed U before it, k₋ = (r − 1 − 2μ)/(1 + r),
// the primary's velocity before and after is V∓ = k₋U, (k₋ + 2μ)U, its
// position X = UT/4 − d/2, and (t₁, U) solve the two linear conditions
// Φ(T/2)(ξ, η⁺) = −(ξ, η⁻) on the deviation from the forced response
// (Φ the damped oscillator's transition matrix), a quadratic in U.
struct SymmetricOrbit {
  double t1 = 0.0, U = 0.0, X = 0.0, before = 0.0, after = 0.0;
};

std::vector<SymmetricOrbit> symmetric_orbits(double zeta, double force, double omega, double mu,
                                             double d, double r) {
  const double period = two_pi / omega, half = period / 2;
  const double detuning = 1 - omega * omega, damping = 2 * zeta * omega;
  const double denominator = detuning * detuning + damping * damping;
  const double P = force * detuning / denominator, Q = force * damping / denominator;
  const double wd = std::sqrt(1 - zeta * zeta), decay = std::exp(-zeta * half);
  const double c = std::cos(wd * half), s = std::sin(wd * half);
  const double phi[2][2] = {{decay * (c + zeta / wd * s), decay * s / wd},
                            {-decay * s / wd, decay * (c - zeta / wd * s)}};
  const double k_minus = (r - 1 - 2 * mu) / (1 + r), k_plus = k_minus + 2 * mu;
  // unknowns (x_p(t₁), ẋ_p(t₁)/ω) = g0 + g1 U from the two linear conditions
  Eigen::Matrix2d A;
  A << -(phi[0][0] + 1), -phi[0][1] * omega, -phi[1][0], -(phi[1][1] + 1) * omega;
  const Eigen::Vector2d b0(-(phi[0][0] + 1) * (-d / 2), -phi[1][0] * (-d / 2));
  const Eigen::Vector2d b1(-((phi[0][0] + 1) * period / 4 + phi[0][1] * k_plus),
                           -(phi[1][0] * period / 4 + phi[1][1] * k_plus + k_minus));
  const Eigen::Vector2d g0 = A.partialPivLu().solve(b0), g1 = A.partialPivLu().solve(b1);
  // |g0 + g1 U|² = P² + Q², the forced response's amplitude squared
  const double qa = g1.squaredNorm(), qb = 2 * g0.dot(g1), qc = g0.squaredNorm() - P * P - Q * Q;
  std::vector<SymmetricOrbit> orbits;
  for (const double sign : {1.0, -1.0}) {
    const double U = (-qb + sign * std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
    const Eigen::Vector2d response = g0 + g1 * U;
    const double cosine = (P * response[0] + Q * response[1]) / (P * P + Q * Q);
    const double sine = (Q * response[0] - P * response[1]) / (P * P + Q * Q);
    orbits.push_back({std::atan2(sine, cosine) / omega, U, U * period / 4 - d / 2, k_minus * U,
                      k_plus * U});
  }
  return orbits;
}

TEST(ImpactDamper, TheAttractorAtOmegaOnePointFiveIsTheClosedFormSymmetricOrbit) {
  const auto model = compiled("impact_damper.toml");
  const double zeta = 0.02, force = 1.0, omega = 1.5, mu = 0.1, d = 2.0, r = 0.6;
  const ModelSystem<4> damper(model, model_parameter_values(*model, {{"zeta", zeta}, {"F", force}, {"omega", omega},
                                                     {"mu", mu}, {"d", d}, {"r", r}}));
  const auto orbits = symmetric_orbits(zeta, force, omega, mu, d, r);
  // the orbit with the faster ball (the other one, U ≈ 0.17, is not reached)
  const SymmetricOrbit orbit = orbits[0];
  ASSERT_GT(orbit.U, 1.0);
  const double period = two_pi / omega;
  // from the scene's initial state, after 400 periods (e^{−ζt} ≈ 3e-15)
  std::vector<ImpactRecorder<ModelSystem<4>>::Impact> impacts;
  const ImpactRecorder<ModelSystem<4>> recorder(damper, impacts);
  EventLog log;
  ASSERT_EQ(run(recorder, {0.0, 0.0, 0.0, 0.5}, 0.0, 404 * period, log).termination,
            Termination::completed);
  std::size_t checked = 0;
  for (const auto& impact : impacts) {
    if (impact.t < 400 * period) continue;
    ++checked;
    // every half period, alternating walls, mirror images
    const double halves = (impact.t - orbit.t1) / (period / 2);
    const long n = std::lround(halves);
    const double sign = n % 2 == 0 ? 1.0 : -1.0;  // + on the right wall (witness 0)
    EXPECT_NEAR(halves, static_cast<double>(n), 1e-9);
    EXPECT_EQ(impact.wall, n % 2 == 0 ? 0u : 1u);
    EXPECT_NEAR(impact.before[0], sign * orbit.X, 1e-9);
    EXPECT_NEAR(impact.before[1], sign * orbit.before, 1e-9);
    EXPECT_NEAR(impact.after[1], sign * orbit.after, 1e-9);
    EXPECT_NEAR(impact.before[3], sign * orbit.U, 1e-9);
    EXPECT_NEAR(impact.after[3], -sign * orbit.U, 1e-9);
  }
  EXPECT_EQ(checked, 8u);
}

}  // namespace
