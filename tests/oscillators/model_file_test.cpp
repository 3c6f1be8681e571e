// Oscillators defined in a scene file's [model] section
// (oscillators/model_file/): the built-in linear impact oscillator and
// bouncing ball written as model files give the same events and Floquet
// multipliers as the hand-written C++ under the same numerical integrator;
// the interpreted slow path agrees with the compiled code; the cache is
// reused, and bypassed where it cannot be made; every kind of bad model file
// is reported at its line and column.
#include <cmath>
#include <cstdlib>
#include <complex>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/simulate/flow.hpp>
#include <impactlab/analysis/floquet.hpp>
#include <impactlab/simulate/simulator.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/bouncing_ball/bouncing_ball.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>

#include "support/model_parameters.hpp"
#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

const std::string examples = std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/";

CompileOptions test_options() {
  CompileOptions options;
  options.cache_directory = ::testing::TempDir() + "impactlab_model_cache_test";
  return options;
}

std::shared_ptr<const CompiledModel> compiled(const std::string& file,
                                              const CompileOptions& options = test_options()) {
  return compile_model(read_model_file(examples + file), options);
}

using impactlab::testing::model_parameter_values;

template <class System>
std::vector<EventRecord> run_events(const System& system, typename System::State x0,
                                    typename System::Mode mode, double t_end) {
  StepperSettings settings;
  settings.rtol = 1e-10;
  settings.atol = 1e-12;
  settings.max_step = system.max_step();
  LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  EventLog log;
  const auto result = with_flow<System>("dopri5", settings, [&](auto& stepper) {
    return simulate(system, stepper, x0, mode, 0.0, t_end, options, log);
  });
  EXPECT_EQ(result.termination, Termination::completed);
  return log.records();
}

void expect_same_events(const std::vector<EventRecord>& expected,
                        const std::vector<EventRecord>& actual, double time_tolerance) {
  ASSERT_EQ(expected.size(), actual.size());
  double worst = 0.0;
  std::size_t worst_event = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    ASSERT_EQ(expected[i].kind, actual[i].kind) << "event " << i;
    ASSERT_EQ(expected[i].wall, actual[i].wall) << "event " << i;
    if (std::fabs(expected[i].t - actual[i].t) > worst) worst_event = i;
    worst = std::max(worst, std::fabs(expected[i].t - actual[i].t));
    EXPECT_NEAR(expected[i].qdot_after, actual[i].qdot_after, 1e-9) << "event " << i;
  }
  EXPECT_LE(worst, time_tolerance) << "at event " << worst_event << " of " << expected.size()
                                   << ", kind " << to_string(expected[worst_event].kind);
}

std::size_t count(const std::vector<EventRecord>& events, EventKind kind) {
  return static_cast<std::size_t>(
      std::count_if(events.begin(), events.end(), [&](const auto& e) { return e.kind == kind; }));
}

TEST(ModelFile, LinearImpactGivesTheBuiltInEvents) {
  const auto model = compiled("linear_impact_model.toml");
  EXPECT_TRUE(model->compiled) << model->slow_path_reason;
  const ModelSystem<2> from_file(model, model_parameter_values(*model, {}), AccumulationTolerance{});
  const LinearImpact built_in{LinearImpactParameters{}};
  EXPECT_DOUBLE_EQ(from_file.max_step(), built_in.max_step());
  const double t_end = 60 * 2 * std::numbers::pi / 2.0;
  const auto expected = run_events(built_in, {0.0, 0.0}, LinearImpact::Mode::free, t_end);
  const auto actual = run_events(from_file, {0.0, 0.0}, ModelSystem<2>::free_mode, t_end);
  EXPECT_GT(count(expected, EventKind::impact), 50u);
  expect_same_events(expected, actual, 1e-12);
}

// A low stop and soft impacts: the impacts chatter, accumulate, and the mass
// rests on the stop until the forcing pulls it away (sticking mode, release).
TEST(ModelFile, LinearImpactChatterAndStickingMatchTheBuiltIn) {
  const auto model = compiled("linear_impact_model.toml");
  LinearImpactParameters p;
  p.sigma = 0.0;
  p.r = 0.5;
  p.omega = 0.5;
  const ModelSystem<2> from_file(model, model_parameter_values(*model, {{"sigma", 0.0}, {"r", 0.5}, {"omega", 0.5}}),
                                 AccumulationTolerance{});
  const LinearImpact built_in{p};
  const double t_end = 20 * 2 * std::numbers::pi / p.omega;
  const auto expected = run_events(built_in, {-0.5, 0.0}, LinearImpact::Mode::free, t_end);
  const auto actual = run_events(from_file, {-0.5, 0.0}, ModelSystem<2>::free_mode, t_end);
  EXPECT_GT(count(expected, EventKind::accumulation), 5u);
  EXPECT_GT(count(expected, EventKind::contact_end), 5u);
  expect_same_events(expected, actual, 1e-12);
}

// The accumulation estimate's local model z̈ = −a − c ż + κ z of the gap
// (contact/accumulation.hpp), derived symbolically from each model's own
// equations, against the coefficients written out by hand: the Duffing
// oscillator's gap h = σ − x has ḧ = −F cos ωt + 2ζẋ + x + βx³, so c = 2ζ
// and κ = ∂ḧ/∂h = −(1 + 3βx²); the bouncing ball's y − z has ḧ = −g − z̈:
// c = κ = 0. The third output is the wall's gap_scale (0: not given).
TEST(ModelFile, TheChatterCoefficientsAreThoseOfTheGapAcceleration) {
  const auto duffing = compiled("duffing_stop.toml");
  const std::vector<double> p =
      model_parameter_values(*duffing, {{"zeta", 0.07}, {"beta", 0.5}, {"F", 1.3}, {"sigma", 0.4}});
  const double x[2] = {0.4, 0.3};
  double out[3];
  duffing->chatter[0](x, 0.9, p.data(), out);
  EXPECT_NEAR(out[0], 2 * 0.07, 1e-15);
  EXPECT_NEAR(out[1], -(1 + 3 * 0.5 * 0.4 * 0.4), 1e-15);
  // its gap_scale: the linear part's forced amplitude F/√((1 − ω²)² + (2ζω)²), ω = 1.5
  EXPECT_NEAR(out[2], 1.3 / std::sqrt(1.25 * 1.25 + 0.21 * 0.21), 1e-15);

  const auto ball = compiled("bouncing_ball_model.toml");
  const std::vector<double> q = model_parameter_values(*ball, {});
  ball->chatter[0](x, 0.9, q.data(), out);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_EQ(out[1], 0.0);
  EXPECT_EQ(out[2], 0.0);  // no gap_scale given

  const auto linear = compiled("linear_impact_model.toml");
  const std::vector<double> l = model_parameter_values(*linear, {{"zeta", 0.05}, {"omega", 0.5}, {"A", 1.0}});
  linear->chatter[0](x, 0.9, l.data(), out);
  EXPECT_NEAR(out[0], 0.1, 1e-15);
  EXPECT_NEAR(out[1], -1.0, 1e-15);
  EXPECT_NEAR(out[2], 1.0 / std::sqrt(0.75 * 0.75 + 0.05 * 0.05), 1e-15);  // A/√D
}

template <class System>
PeriodicOrbit<typename System::State, typename System::Mode> orbit_of(
    const System& system, typename System::State x0, typename System::Mode mode, double omega) {
  const FlowSetup setup;  // dopri5, rtol 1e-10, atol 1e-12
  const double period = 2 * std::numbers::pi / omega;
  EventLog log(false);
  StepperSettings settings = stepper_settings(system, setup);
  const auto transient = with_flow<System>(setup.method, settings, [&](auto& stepper) {
    return simulate(system, stepper, x0, mode, 0.0, 50 * period, loop_options(setup), log);
  });
  return locate_periodic_orbit(system, setup, transient.state, transient.mode, 50 * period, period);
}

TEST(ModelFile, FloquetMultipliersMatchTheBuiltIns) {
  {
    const auto model = compiled("linear_impact_model.toml");
    const auto expected = orbit_of(LinearImpact{LinearImpactParameters{}}, {0.0, 0.0},
                                   LinearImpact::Mode::free, 2.0);
    const auto actual =
        orbit_of(ModelSystem<2>(model, model_parameter_values(*model, {}), AccumulationTolerance{}), {0.0, 0.0}, ModelSystem<2>::free_mode, 2.0);
    ASSERT_TRUE(expected.converged && actual.converged);
    for (int i = 0; i < 2; ++i)
      EXPECT_LE(std::abs(expected.multipliers[i] - actual.multipliers[i]), 1e-10);
  }
  {
    const auto model = compiled("bouncing_ball_model.toml");
    const auto expected = orbit_of(BouncingBall{BouncingBallParameters{}}, {0.05, 0.0},
                                   BouncingBall::Mode::free, 30.0);
    const auto actual = orbit_of(ModelSystem<2>(model, model_parameter_values(*model, {}), AccumulationTolerance{}), {0.05, 0.0},
                                 ModelSystem<2>::free_mode, 30.0);
    ASSERT_TRUE(expected.converged && actual.converged);
    for (int i = 0; i < 2; ++i)
      EXPECT_LE(std::abs(expected.multipliers[i] - actual.multipliers[i]), 1e-10);
  }
}

// Chatter and riding (r = 0.8 and 0.3, from rest): the same sequence of events. In a
// chatter each impact at relative speed u is located to δh/u (δh ≈ 1e-18 m,
// the round-off of the gap y − z), and the error grows along the sequence up
// to the accumulation point; the two codes round differently (GiNaC orders
// sums its own way), so the times agree to 1e-9 s here, not 1e-12.
TEST(ModelFile, BouncingBallChatterAndRidingGiveTheBuiltInSequence) {
  const auto model = compiled("bouncing_ball_model.toml");
  for (const double r : {0.8, 0.3}) {
    BouncingBallParameters p;
    p.r = r;
    const BouncingBall built_in{p};
    const ModelSystem<2> from_file(model, model_parameter_values(*model, {{"r", r}}), AccumulationTolerance{});
    const double t_end = 40 * 2 * std::numbers::pi / p.omega;
    const auto expected = run_events(built_in, {0.05, 0.0}, BouncingBall::Mode::free, t_end);
    const auto actual = run_events(from_file, {0.05, 0.0}, ModelSystem<2>::free_mode, t_end);
    EXPECT_GT(count(expected, EventKind::contact_start), 20u);
    EXPECT_GT(count(expected, EventKind::contact_end), 20u);
    expect_same_events(expected, actual, 1e-9);
  }
}

TEST(ModelFile, TheCacheIsReusedAndTheSlowPathSaysSo) {
  const auto first = compiled("linear_impact_model.toml");
  const auto second = compiled("linear_impact_model.toml");
  ASSERT_TRUE(second->compiled);
  EXPECT_TRUE(second->from_cache);
  EXPECT_EQ(first->library, second->library);

  CompileOptions broken = test_options();
  broken.compiler = {"/nonexistent/cc"};
  broken.cache_directory += "_broken_compiler";
  std::filesystem::remove_all(broken.cache_directory);
  const auto slow = compiled("linear_impact_model.toml", broken);
  EXPECT_FALSE(slow->compiled);
  EXPECT_NE(slow->slow_path_reason.find("compiler"), std::string::npos) << slow->slow_path_reason;

  // a cache folder that cannot be made is bypassed: compiled, not kept
  CompileOptions unwritable = test_options();
  unwritable.cache_directory = "/proc/impactlab_cache";
  const auto without_cache = compiled("linear_impact_model.toml", unwritable);
  EXPECT_TRUE(without_cache->compiled) << without_cache->slow_path_reason;
  EXPECT_TRUE(without_cache->library.empty()) << without_cache->library;
  EXPECT_NE(without_cache->cache_note.find("cache directory /proc/impactlab_cache cannot be created"),
            std::string::npos)
      << without_cache->cache_note;

  // the interpreted evaluator gives the compiled code's events
  const double t_end = 30 * std::numbers::pi;
  const auto fast_events = run_events(ModelSystem<2>(first, model_parameter_values(*first, {}), AccumulationTolerance{}), {0.0, 0.0},
                                      ModelSystem<2>::free_mode, t_end);
  const auto slow_events = run_events(ModelSystem<2>(slow, model_parameter_values(*slow, {}), AccumulationTolerance{}), {0.0, 0.0},
                                      ModelSystem<2>::free_mode, t_end);
  expect_same_events(fast_events, slow_events, 1e-12);
}

// The compiler runs from an argument vector, never a shell: a cache
// directory whose path holds quotes, ';', command substitutions and spaces
// compiles and loads, and none of the commands written into it runs.
TEST(ModelFile, ACacheDirectoryWithShellSyntaxCompilesAndRunsNoCommand) {
  const impactlab::testing::ScratchFolder base;
  const std::filesystem::path marker = base / "injected";
  CompileOptions hostile = test_options();
  hostile.cache_directory = (base / ("it's a cache; touch " + marker.string() + "; $(touch " +
                                     marker.string() + ") `touch " + marker.string() + "` end"))
                                .string();
  const auto model = compiled("linear_impact_model.toml", hostile);
  ASSERT_TRUE(model->compiled) << model->slow_path_reason;
  EXPECT_FALSE(model->from_cache);
  EXPECT_EQ(model->library.rfind(hostile.cache_directory, 0), 0u) << model->library;
  EXPECT_TRUE(std::filesystem::exists(model->library));
  EXPECT_FALSE(std::filesystem::exists(marker));
  // the loaded code is the model's: ẋ' = A cos ωt − 2ζẋ − x at the defaults
  const std::vector<double> p = model_parameter_values(*model, {});
  const double x[2] = {0.3, -0.7}, t = 0.4;
  double rhs[2];
  model->free_rhs(x, t, p.data(), rhs);
  EXPECT_EQ(rhs[0], -0.7);
  EXPECT_NEAR(rhs[1], 1.0 * std::cos(2.0 * t) - 2 * 0.05 * -0.7 - 0.3, 1e-15);
}

// $IMPACTLAB_CC may carry flags of its own: split on spaces into the argument
// vector; a compiler that starts but fails falls back with its first line.
TEST(ModelFile, TheCompilerCommandMayCarryFlags) {
  ASSERT_EQ(::setenv("IMPACTLAB_CC", "  cc  -O1 -g ", 1), 0);
  const CompileOptions from_environment = compile_options_from_environment();
  ::unsetenv("IMPACTLAB_CC");
  EXPECT_EQ(from_environment.compiler, (std::vector<std::string>{"cc", "-O1", "-g"}));
  CompileOptions with_flags = test_options();
  with_flags.compiler = from_environment.compiler;
  with_flags.cache_directory += "_with_flags";
  std::filesystem::remove_all(with_flags.cache_directory);
  const auto model = compiled("linear_impact_model.toml", with_flags);
  EXPECT_TRUE(model->compiled) << model->slow_path_reason;
  EXPECT_FALSE(model->from_cache);

  CompileOptions failing = test_options();
  failing.compiler = {"cc", "--impactlab-no-such-flag"};
  failing.cache_directory += "_failing_compiler";
  std::filesystem::remove_all(failing.cache_directory);
  const auto slow = compiled("linear_impact_model.toml", failing);
  EXPECT_FALSE(slow->compiled);
  EXPECT_NE(slow->slow_path_reason.find("the C compiler 'cc --impactlab-no-such-flag' failed (status"),
            std::string::npos)
      << slow->slow_path_reason;
  // the compiler's own first line, naming the flag again after the status
  const std::string& reason = slow->slow_path_reason;
  EXPECT_NE(reason.find("impactlab-no-such-flag", reason.find("(status")), std::string::npos) << reason;
  // nothing left behind but the directory
  EXPECT_TRUE(std::filesystem::is_empty(failing.cache_directory));
}

// --- bad model files: one line FILE:LINE:COL: message ---

std::string error_of(const std::string& text) {
  const impactlab::testing::ScratchFolder scratch;
  const std::string path = (scratch / "bad_model.toml").string();
  std::ofstream(path) << text;
  try {
    const auto model = compile_model(read_model_file(path), test_options());
    check_initial_values(*model, {0.0, 0.0}, 0.0, model_parameter_values(*model, {}));
  } catch (const BadInput& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos);
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << message;
    return message.substr(path.size() + 1);
  }
  return "no error";
}

const std::string good_head = R"([model]
states = ["x", "v"]
forcing_frequency = "omega"
[model.parameters]
omega = 1.0
k = 2.0
)";

// lines 7-9: the right-hand side, its second equation written by each case
std::string with_rhs(const std::string& v_equation, const std::string& rest = "") {
  return good_head + "[model.rhs]\nx = \"v\"\nv = \"" + v_equation + "\"\n" + rest;
}

const std::string wall_head = "[[model.walls]]\nwitness = \"1 - x\"\n";  // lines 10-11

TEST(ModelFileErrors, EachIsReportedAtItsLineAndColumn) {
  // the expression of line 9 starts at column 6 (after v = ")
  EXPECT_EQ(error_of(with_rhs("-k*x +* v")).substr(0, 20), "9:12: unexpected '*'");
  EXPECT_EQ(error_of(with_rhs("-k*y")).substr(0, 26), "9:9: unknown symbol 'y' in");
  EXPECT_EQ(error_of(with_rhs("k/(x - x)")).substr(0, 50),
            "9:7: division by an expression that is always zero");
  EXPECT_EQ(error_of(with_rhs("sin(x, v)")).substr(0, 39), "9:6: function 'sin' takes 1 argument(s)");
  // NaN at the initial state x = 0
  const std::string not_a_number = error_of(with_rhs("sqrt(x - 1)"));
  EXPECT_EQ(not_a_number.substr(0, 18), "9:6: evaluates to ") << not_a_number;
  EXPECT_NE(not_a_number.find("nan at the initial state"), std::string::npos) << not_a_number;
  // a circular definition: found where the cycle closes, the 'a' of line 9
  EXPECT_EQ(error_of(with_rhs("a", "[model.definitions]\na = \"b + 1\"\nb = \"2*a\"\n")).substr(0, 34),
            "12:8: circular definition: 'a' dep");
  // a missing reset and a witness without direction: at the wall's table (line 10)
  const std::string missing_reset = error_of(with_rhs("-x", wall_head + "direction = \"falling\"\n"));
  EXPECT_EQ(missing_reset.substr(0, 3), "10:");
  EXPECT_NE(missing_reset.find("missing reset"), std::string::npos) << missing_reset;
  const std::string no_direction =
      error_of(with_rhs("-x", wall_head + "reset = { velocity = \"v\", restitution = \"0.8\" }\n"));
  EXPECT_EQ(no_direction.substr(0, 3), "10:");
  EXPECT_NE(no_direction.find("without direction"), std::string::npos) << no_direction;
  // a dimension mismatch: an equation missing (at [model.rhs], line 7) or too many
  const std::string missing = error_of(good_head + "[model.rhs]\nx = \"v\"\n");
  EXPECT_EQ(missing.substr(0, 2), "7:");
  EXPECT_NE(missing.find("dimension mismatch"), std::string::npos) << missing;
  const std::string extra = error_of(with_rhs("-x") + "w = \"1\"\n");
  EXPECT_EQ(extra.substr(0, 6), "10:6: ") << extra;
  EXPECT_NE(extra.find("dimension mismatch"), std::string::npos) << extra;
  // a sticking wall's optional gap_scale (line 18) is an expression like the others
  const std::string sticking_wall =
      wall_head + "direction = \"falling\"\nreset = { velocity = \"v\", restitution = \"0.8\" }\n"
                  "[model.walls.sticking]\nrhs = { x = \"0\", v = \"0\" }\nstate = { x = \"1\", v = \"0\" }\n"
                  "force = \"1\"\ngap_scale = \"2*q\"\n";
  EXPECT_EQ(error_of(with_rhs("-x", sticking_wall)).substr(0, 26), "18:16: unknown symbol 'q' ");
  // malformed TOML itself
  EXPECT_EQ(error_of(good_head + "[model.rhs\n").substr(0, 2), "7:");
}

}  // namespace
