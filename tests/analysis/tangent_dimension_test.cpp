// The analyses' tangent space is the system's own (core/has_jacobian.hpp):
// all N states of a model file, so that saltation, the variational system,
// Floquet multipliers, the largest Lyapunov exponent, Newton shooting and
// continuation run on 4-state models. Checked against independent results:
// * a 4-state model file made of the linear impact oscillator beside an
//   uncoupled, wall-free damped oscillator u'' + 2ζ₂u' + u = 0: the Floquet
//   multipliers of its period-1 orbit are the closed-form ones of the linear
//   impact oscillator (tests/support/linear_impact_closed_form.hpp) and
//   exp((−ζ₂ ± i√(1 − ζ₂²)) T) of the free pair, to 1e-10; its largest
//   Lyapunov exponent just below the period doubling is log |μ_max| / T of
//   that closed form; `continue` in ω (the dynamic-size driver) locates the
//   closed form's period doubling to 1e-9 relative; with a sticking wall the
//   model is refused the analyses (its contact linearisation pins all states);
// * the impact damper (oscillators/model_file/examples/impact_damper.toml):
//   the monodromy matrix of a periodic orbit against central finite
//   differences of the full event-driven return map (the base system alone,
//   no variational equations), and the largest Lyapunov exponent on the
//   orbit against log |μ_max| / T of its multipliers;
// * `periodic` and `continue` from the command line on impact_damper.toml:
//   exit 0 and four multipliers in periodic.json, branch.csv and points.csv.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/api/scene_loading.hpp>
#include <impactlab/io/bad_input.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>

#include "support/linear_impact_closed_form.hpp"
#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;
namespace fs = std::filesystem;
using Complex = std::complex<double>;
using System4 = ModelSystem<4>;

const std::string examples = std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/";

static_assert(tangent_dimension_of<System4> == 4);
static_assert(tangent_dimension_of<ModelSystem<2>> == 2);
static_assert(tangent_dimension_of<LinearImpact> == 2);

using impactlab::testing::ScratchFolder;

// where composite() writes the 4-state model's scene file, for this process
const ScratchFolder& composite_folder() {
  static const ScratchFolder folder;
  return folder;
}

CompileOptions compile_options() {
  CompileOptions options;
  options.cache_directory = ::testing::TempDir() + "impactlab_tangent_dimension_cache";
  return options;
}

// The linear impact oscillator (the built-in's defaults: ζ = 0.05, A = 1,
// σ = 0.2, r = 0.8) and, uncoupled, u'' + 2ζ₂u' + u = 0 with no wall.
constexpr const char* composite_model = R"toml(name = "linear_impact_beside_free_oscillator"
description = "the linear impact oscillator and an uncoupled damped oscillator (test)"

[initial]
x = 0.0
x_dot = 0.0
u = 0.0
u_dot = 0.0

[integrator]
method = "rk8pd"
rtol = 1e-12
atol = 1e-13

[model]
states = ["x", "x_dot", "u", "u_dot"]
forcing_frequency = "omega"
max_step = "(2*pi/omega + 2*pi - abs(2*pi/omega - 2*pi)) / 2 / 16"

[model.parameters]
zeta  = { default = 0.05, min = 0.0 }
A     = { default = 1.0 }
omega = { default = 2.0, min = 0.0, min_open = true }
sigma = { default = 0.2 }
r     = { default = 0.8, min = 0.0, max = 1.0 }
zeta2 = { default = 0.1, min = 0.0, max = 1.0, max_open = true }

[model.rhs]
x = "x_dot"
x_dot = "A*cos(omega*t) - 2*zeta*x_dot - x"
u = "u_dot"
u_dot = "-2*zeta2*u_dot - u"

[[model.walls]]
name = "stop"
side = 1
witness = "sigma - x"
direction = "falling"
reset = { velocity = "x_dot", restitution = "r", position = "x" }
)toml";

std::shared_ptr<const CompiledModel> composite() {
  static const std::shared_ptr<const CompiledModel> model = [] {
    const fs::path file = composite_folder() / "composite.toml";
    std::ofstream(file) << composite_model;
    return compile_model(read_model_file(file.string()), compile_options());
  }();
  return model;
}

// The parameter values in the model's order: the defaults, with omega given.
std::vector<double> with_omega(const CompiledModel& model, double omega) {
  std::vector<double> p;
  for (const auto& parameter : model.parameters)
    p.push_back(parameter.name == "omega" ? omega : parameter.default_value);
  return p;
}

// Every expected multiplier has an actual one within `tolerance` (the two
// lists matched greedily, nearest first), and the actual list is sorted by
// decreasing modulus.
void expect_same_multipliers(std::vector<Complex> expected, const std::vector<Complex>& actual,
                             double tolerance) {
  ASSERT_EQ(expected.size(), actual.size());
  std::vector<bool> used(actual.size(), false);
  for (const Complex& want : expected) {
    std::size_t best = actual.size();
    for (std::size_t k = 0; k < actual.size(); ++k)
      if (!used[k] && (best == actual.size() || std::abs(actual[k] - want) < std::abs(actual[best] - want)))
        best = k;
    used[best] = true;
    EXPECT_LE(std::abs(actual[best] - want), tolerance) << "expected " << want << ", nearest " << actual[best];
  }
  for (std::size_t k = 1; k < actual.size(); ++k)
    EXPECT_GE(std::abs(actual[k - 1]), std::abs(actual[k]));
}

const FlowSetup tight{"rk8pd", 1e-13, 1e-14};

TEST(TangentDimension, FourStateMultipliersAreTheLinearImpactOnesAndTheFreePair) {
  const auto model = composite();
  for (const double omega : {2.0, 2.4}) {
    LinearImpactParameters p;
    p.omega = omega;
    const impactlab::testing::LinearImpactClosedForm closed(p);
    const auto orbit_closed = closed.orbit();
    ASSERT_TRUE(orbit_closed.has_value());
    const double period = closed.period();
    // the guess: the closed form's state on the section t = 0, and the free
    // pair away from its fixed point (Newton brings it to 0)
    const auto [x, v] = closed.state_after(orbit_closed->impact_time, orbit_closed->velocity,
                                           period - orbit_closed->impact_time);
    const System4 system(model, with_omega(*model, omega));
    const auto orbit = locate_periodic_orbit(system, tight, System4::State{x, v, 0.3, -0.2},
                                             System4::free_mode, 0.0, period);
    ASSERT_TRUE(orbit.converged) << omega;
    EXPECT_NEAR(orbit.state[2], 0.0, 1e-12);
    EXPECT_NEAR(orbit.state[3], 0.0, 1e-12);
    const double zeta2 = 0.1, damped = std::sqrt(1.0 - zeta2 * zeta2);
    const std::vector<Complex> expected = {
        orbit_closed->multipliers[0], orbit_closed->multipliers[1],
        std::exp(Complex(-zeta2, damped) * period), std::exp(Complex(-zeta2, -damped) * period)};
    expect_same_multipliers(expected, {orbit.multipliers.begin(), orbit.multipliers.end()}, 1e-10);
  }
}

TEST(TangentDimension, FourStateLyapunovExponentIsTheClosedFormsLargestMultiplier) {
  // just below the period doubling (ω = 2.26530): the linear impact
  // oscillator's multipliers are real and distinct, the largest near −1, well
  // above the free pair's modulus exp(−ζ₂T) ≈ 0.76
  const double omega = 2.263;
  LinearImpactParameters p;
  p.omega = omega;
  const impactlab::testing::LinearImpactClosedForm closed(p);
  const auto orbit_closed = closed.orbit();
  ASSERT_TRUE(orbit_closed.has_value());
  ASSERT_EQ(orbit_closed->multipliers[0].imag(), 0.0);
  const double period = closed.period();
  const auto [x, v] = closed.state_after(orbit_closed->impact_time, orbit_closed->velocity,
                                         period - orbit_closed->impact_time);
  const auto model = composite();
  const System4 system(model, with_omega(*model, omega));
  const auto orbit = locate_periodic_orbit(system, tight, System4::State{x, v, 0.0, 0.0},
                                           System4::free_mode, 0.0, period);
  ASSERT_TRUE(orbit.converged);
  const auto lyapunov = largest_lyapunov_exponent(system, tight, orbit.state, orbit.mode, 0.0,
                                                  period, 400, 100);
  ASSERT_EQ(lyapunov.termination, Termination::completed);
  EXPECT_NEAR(lyapunov.exponent, std::log(std::abs(orbit_closed->multipliers[0])) / period, 1e-6);
}

TEST(TangentDimension, FourStateContinuationLocatesTheLinearImpactPeriodDoubling) {
  // the closed form's period doubling: 1 + tr M + det M = 0 of its 2 × 2
  // monodromy (ζ = 0.05, A = 1, σ = 0.2, r = 0.8), ω ≈ 2.26530
  const double expected = impactlab::testing::root_by_toms748(
      [](double omega) {
        LinearImpactParameters p;
        p.omega = omega;
        const auto orbit = impactlab::testing::LinearImpactClosedForm(p).orbit();
        return orbit ? 1.0 + orbit->trace + orbit->determinant : NAN;
      },
      2.24, 2.29);
  composite();  // writes the scene file
  const Scene scene = load_scene(
      (composite_folder() / "composite.toml").string());
  ContinuationJob job;
  job.parameter = "omega";
  job.from = 2.2;
  job.to = 2.32;
  const auto result = continue_orbit(scene, job);
  ASSERT_TRUE(result.available) << result.note;
  EXPECT_EQ(result.dimension, 4u);
  const auto& branch = result.branches.at(0).result;
  EXPECT_EQ(branch.stop_reason, impactlab::StopReason::end_of_range) << branch.stop_detail;
  std::vector<BifurcationPoint> doublings;
  for (const auto& point : branch.points) {
    EXPECT_NE(point.type, impactlab::BifurcationType::fold);
    if (point.type == impactlab::BifurcationType::period_doubling) doublings.push_back(point);
  }
  ASSERT_EQ(doublings.size(), 1u);
  EXPECT_TRUE(doublings[0].located);
  EXPECT_NEAR(doublings[0].parameter, expected, 1e-9 * expected);
  ASSERT_EQ(doublings[0].multipliers.size(), 4u);
  ASSERT_EQ(doublings[0].state.size(), 4u);
  EXPECT_NEAR(doublings[0].multipliers[0].real(), -1.0, 1e-7);
  EXPECT_NEAR(doublings[0].state[2], 0.0, 1e-10);  // the free pair at rest
  EXPECT_NEAR(doublings[0].state[3], 0.0, 1e-10);
  // stable before the doubling, unstable after it
  for (const auto& point : branch.branch) {
    ASSERT_EQ(point.multipliers.size(), 4u);
    if (std::fabs(point.parameter - expected) > 1e-6) {
      EXPECT_EQ(point.stable, point.parameter < expected) << point.parameter;
    }
  }
}

// A sticking mode pins the whole state (ModelSystem::pinned, the collapse at
// an accumulation): right for one degree of freedom only, so a 4-state model
// with a sticking wall is offered no analysis that would use it.
TEST(TangentDimension, FourStateModelWithAStickingWallIsRefusedTheAnalyses) {
  std::string text = composite_model;
  text.replace(text.find("name = \"linear_impact_beside_free_oscillator\""),
               std::string("name = \"linear_impact_beside_free_oscillator\"").size(),
               "name = \"linear_impact_sticking_beside_free_oscillator\"");
  text += "sticking = { rhs = { x = \"0\", x_dot = \"0\", u = \"u_dot\", "
          "u_dot = \"-2*zeta2*u_dot - u\" }, state = { x = \"sigma\", x_dot = \"0\", u = \"u\", "
          "u_dot = \"u_dot\" }, "
          "force = \"A*cos(omega*t) - sigma\" }\n";
  const ScratchFolder scratch;
  const fs::path file = scratch / "sticking.toml";
  std::ofstream(file) << text;
  const Scene scene = load_scene(file.string());
  const PeriodicResult periodic_result = periodic(scene, PeriodicRequest{});
  EXPECT_FALSE(periodic_result.available);
  EXPECT_NE(periodic_result.note.find("sticking"), std::string::npos) << periodic_result.note;
  ContinuationJob job;
  job.parameter = "omega";
  job.from = 2.0;
  job.to = 2.1;
  try {
    continue_orbit(scene, job);
    ADD_FAILURE() << "continue_orbit ran on a 4-state model with a sticking wall";
  } catch (const BadInput& error) {
    EXPECT_EQ(error.key(), "oscillator");
    EXPECT_NE(std::string(error.what()).find("sticking"), std::string::npos) << error.what();
  }
}

// --- the impact damper ---

// rk8pd at rtol = atol = 1e-11: at 1e-12 and below the event loop stops on
// this orbit with no_progress within a few hundred periods (the same with
// `impactlab poincare`; a limit of the event location, not of the tangent
// space)
const FlowSetup damper_setup{"rk8pd", 1e-11, 1e-11};

std::shared_ptr<const CompiledModel> impact_damper() {
  static const auto model =
      compile_model(read_model_file(examples + "impact_damper.toml"), compile_options());
  return model;
}

System4::State flow(const System4& system, const FlowSetup& setup, System4::State x0, double t0,
                    double t1, std::uint64_t* impacts = nullptr) {
  EventLog log(false);
  const auto run = with_flow<System4>(setup.method, stepper_settings(system, setup),
                                         [&](auto& stepper) {
                                           return simulate(system, stepper, x0, System4::free_mode,
                                                           t0, t1, loop_options(setup), log);
                                         });
  EXPECT_EQ(run.termination, Termination::completed);
  EXPECT_EQ(run.mode, System4::free_mode);
  if (impacts) *impacts = log.count(EventKind::impact);
  return run.state;
}

struct DamperOrbit {
  System4 system;
  double period;
  PeriodicOrbit<System4::State, ModelMode, 4> orbit;
  std::uint64_t impacts;
};

// A stable period-1 orbit with two impacts per period, from the scene's
// initial state after a transient of 200 forcing periods: the shipped
// parameters with ζ = 0.1, ω = 1.38, where the largest multiplier (≈ −0.83)
// is real and well above the others (|μ| ≈ 0.53), so that a tangent vector
// aligns with it within a few dozen periods.
DamperOrbit damper_orbit() {
  const auto model = impact_damper();
  std::vector<double> p;
  for (const auto& parameter : model->parameters)
    p.push_back(parameter.name == "zeta"    ? 0.1
                : parameter.name == "omega" ? 1.38
                                            : parameter.default_value);
  const System4 system(model, p);
  const double period = 2.0 * std::numbers::pi / system.forcing_frequency();
  // the transient under the scene's integrator settings (its chatter at the
  // start is resolved there; rk8pd at 1e-13 stops in it with no_progress)
  const System4::State start = flow(system, FlowSetup{}, {0.0, 0.0, 0.0, 0.5}, 0.0, 200 * period);
  const auto orbit =
      locate_periodic_orbit(system, damper_setup, start, System4::free_mode, 200 * period, period);
  std::uint64_t impacts = 0;
  flow(system, damper_setup, orbit.state, 200 * period, 201 * period, &impacts);
  return {system, period, orbit, impacts};
}

TEST(TangentDimension, ImpactDamperMonodromyMatchesFiniteDifferencesOfTheReturnMap) {
  const DamperOrbit damper = damper_orbit();
  ASSERT_TRUE(damper.orbit.converged) << "residual " << damper.orbit.residual;
  ASSERT_GE(damper.impacts, 1u);
  const double t0 = 200 * damper.period, t1 = t0 + damper.period;
  TangentMatrixOf<4> reference{};
  const double h = 1e-5;
  for (int column = 0; column < 4; ++column) {
    auto plus = damper.orbit.state, minus = damper.orbit.state;
    plus[column] += h;
    minus[column] -= h;
    const auto xp = flow(damper.system, damper_setup, plus, t0, t1);
    const auto xm = flow(damper.system, damper_setup, minus, t0, t1);
    for (int row = 0; row < 4; ++row) reference[row][column] = (xp[row] - xm[row]) / (2.0 * h);
  }
  double scale = 0.0;
  for (const auto& row : reference)
    for (double value : row) scale = std::max(scale, std::fabs(value));
  ASSERT_GT(scale, 0.0);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(damper.orbit.monodromy[i][j], reference[i][j], 1e-6 * scale)
          << "entry " << i << j;
  // the multipliers are those of the monodromy matrix (Eigen's real Schur
  // form, checked here through its invariants: the sum and the product)
  Complex sum = 0.0, product = 1.0;
  for (const Complex& m : damper.orbit.multipliers) {
    sum += m;
    product *= m;
  }
  double trace = 0.0;
  for (int i = 0; i < 4; ++i) trace += damper.orbit.monodromy[i][i];
  EXPECT_NEAR(sum.real(), trace, 1e-12 * (1.0 + std::fabs(trace)));
  EXPECT_NEAR(sum.imag(), 0.0, 1e-12);
  EXPECT_NEAR(product.imag(), 0.0, 1e-12);
}

TEST(TangentDimension, ImpactDamperLyapunovExponentOfItsPeriodicOrbit) {
  const DamperOrbit damper = damper_orbit();
  ASSERT_TRUE(damper.orbit.converged);
  const double t0 = 200 * damper.period;
  const auto lyapunov = largest_lyapunov_exponent(damper.system, damper_setup, damper.orbit.state,
                                                  damper.orbit.mode, t0, damper.period, 400, 100);
  ASSERT_EQ(lyapunov.termination, Termination::completed);
  const double expected = std::log(std::abs(damper.orbit.multipliers[0])) / damper.period;
  EXPECT_NEAR(lyapunov.exponent, expected, 1e-6) << "multipliers " << damper.orbit.multipliers[0]
                                                 << ", " << damper.orbit.multipliers[1];
}

// --- the command line ---

std::vector<std::string> csv_row(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  return fields;
}

TEST(TangentDimension, PeriodicAndContinueRunOnTheImpactDamperFromTheCommandLine) {
  const ScratchFolder dir;
  const std::vector<std::string> cache = {"IMPACTLAB_CACHE_DIR=" + (dir / "cache").string()};
  const std::string scene = examples + "impact_damper.toml";
  {
    const auto run = impactlab::testing::run_impactlab(
        {"periodic", scene, "--period", "1", "--set", "omega=1.5", "--quiet", "--out",
         (dir / "periodic").string()},
        {.environment = cache, .limit_s = 120});
    ASSERT_EQ(run.status, 0) << run.err;
    const auto document =
        nlohmann::json::parse(impactlab::testing::slurp(dir / "periodic" / "periodic.json"));
    EXPECT_TRUE(document["converged"].get<bool>());
    ASSERT_EQ(document["floquet_multipliers"].size(), 4u);
    ASSERT_EQ(document["monodromy"].size(), 4u);
    EXPECT_EQ(document["monodromy"][0].size(), 4u);
    double product = 1.0;
    for (const auto& m : document["floquet_multipliers"]) product *= m["abs"].get<double>();
    EXPECT_GT(product, 0.0);
  }
  {
    const auto run = impactlab::testing::run_impactlab(
        {"continue", scene, "--param", "omega=1.5:1.6", "--max-points", "20", "--quiet", "--out",
         (dir / "continue").string()},
        {.environment = cache, .limit_s = 300});
    ASSERT_EQ(run.status, 0) << run.err;
    std::ifstream branch(dir / "continue" / "branch.csv");
    std::string header, line;
    ASSERT_TRUE(std::getline(branch, header));
    const auto columns = csv_row(header);
    for (const char* name : {"q", "qdot", "state3", "state4", "multiplier4_re", "multiplier4_im",
                             "multiplier4_abs"})
      EXPECT_NE(std::find(columns.begin(), columns.end(), name), columns.end()) << name;
    int rows = 0;
    while (std::getline(branch, line)) {
      ++rows;
      const auto fields = csv_row(line);
      ASSERT_EQ(fields.size(), columns.size()) << line;
      const auto at = [&](const std::string& name) {
        return std::stod(fields[std::find(columns.begin(), columns.end(), name) - columns.begin()]);
      };
      // the reported moduli are those of the reported multipliers, largest first
      for (int k = 1; k <= 4; ++k) {
        const std::string m = "multiplier" + std::to_string(k);
        EXPECT_NEAR(at(m + "_abs"), std::hypot(at(m + "_re"), at(m + "_im")), 1e-12 * (1.0 + at(m + "_abs")));
        if (k > 1) {
          EXPECT_LE(at(m + "_abs"), at("multiplier" + std::to_string(k - 1) + "_abs"));
        }
      }
    }
    EXPECT_GE(rows, 2);
    std::ifstream points(dir / "continue" / "points.csv");
    ASSERT_TRUE(std::getline(points, header));
    EXPECT_NE(header.find("multiplier4_im"), std::string::npos);
  }
  {
    // the impact section's state is (phase, the other states before the
    // impact): four components here. The orbit's multipliers do not depend
    // on the section, so the impact map's Neimark–Sacker point and its
    // first point's multipliers are the stroboscopic map's
    std::map<std::string, std::pair<double, std::vector<double>>> found;
    for (const std::string section : {"strobe", "impact:1"}) {
      const auto out = dir / ("section_" + section.substr(0, 6));
      const auto run = impactlab::testing::run_impactlab(
          {"continue", scene, "--param", "omega=2:2.5", "--section", section, "--quiet", "--out",
           out.string()},
          {.environment = cache, .limit_s = 300});
      ASSERT_EQ(run.status, 0) << section << ": " << run.err;
      std::ifstream branch(out / "branch.csv"), points(out / "points.csv");
      std::string header, line;
      ASSERT_TRUE(std::getline(branch, header));
      ASSERT_TRUE(std::getline(branch, line));
      const auto columns = csv_row(header);
      const auto first = csv_row(line);
      std::vector<double> moduli;
      for (int k = 1; k <= 4; ++k) {
        const auto column = std::find(columns.begin(), columns.end(),
                                      "multiplier" + std::to_string(k) + "_abs");
        ASSERT_NE(column, columns.end());
        moduli.push_back(std::stod(first[column - columns.begin()]));
      }
      double neimark_sacker = NAN;
      ASSERT_TRUE(std::getline(points, header));
      while (std::getline(points, line)) {
        const auto fields = csv_row(line);
        if (fields.at(0) == "neimark_sacker") neimark_sacker = std::stod(fields.at(1));
      }
      found[section] = {neimark_sacker, moduli};
    }
    const auto& [strobe_point, strobe_moduli] = found["strobe"];
    const auto& [impact_point, impact_moduli] = found["impact:1"];
    ASSERT_TRUE(std::isfinite(strobe_point));
    EXPECT_NEAR(impact_point, strobe_point, 1e-8);
    for (std::size_t k = 0; k < 4; ++k)
      EXPECT_NEAR(impact_moduli[k], strobe_moduli[k], 1e-9) << k;
  }
}

}  // namespace
