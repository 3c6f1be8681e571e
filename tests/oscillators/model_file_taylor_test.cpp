// The Taylor stepper on model files (oscillators/model_file/series_program.hpp):
// the linear impact oscillator written as a model file, integrated by its
// series, gives the events of the built-in oscillator's closed-form flow,
// through chatter, sticking and release; the Duffing oscillator with a stop
// (a cube) and a model with every function that has a series those of a
// tight Runge–Kutta run, with the variational equations' fundamental
// matrix; a model with an operation that has no series says which, and the
// programs over doubles are the compiled kernels.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/analysis/variational.hpp>
#include <impactlab/integrate/stepper_dispatch.hpp>
#include <impactlab/oscillators/linear_impact/linear_impact.hpp>
#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_system.hpp>
#include <impactlab/simulate/simulator.hpp>

#include "support/model_parameters.hpp"
#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab;

static_assert(HasSeriesRhs<ModelSystem<2>> && HasTapeRhs<ModelSystem<2>>);
static_assert(HasSeriesRhs<ModelSystem<4>> && HasTapeRhs<ModelSystem<4>>);

const std::string examples = std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/";

CompileOptions test_options() {
  CompileOptions options;
  options.cache_directory = ::testing::TempDir() + "impactlab_model_taylor_test";
  return options;
}

std::shared_ptr<const CompiledModel> compiled_example(const std::string& file) {
  return compile_model(read_model_file(examples + file), test_options());
}

std::shared_ptr<const CompiledModel> compiled_text(const std::string& text) {
  const impactlab::testing::ScratchFolder scratch;
  const std::string path = (scratch / "model.toml").string();
  std::ofstream(path) << text;
  return compile_model(read_model_file(path), test_options());
}

using impactlab::testing::model_parameter_values;

// A run of `method` at rtol (atol and the grazing tolerance a hundredth of
// it) from x0 in the free mode over [0, t_end], its events in `log`
template <class System>
RunResult<typename System::State, typename System::Mode> run(const System& system,
                                                            typename System::State x0,
                                                            const std::string& method, double rtol,
                                                            double t_end, EventLog& log) {
  StepperSettings settings;
  settings.rtol = rtol;
  settings.atol = rtol / 100.0;
  settings.max_step = system.max_step();
  LoopOptions options;
  options.location.grazing_tolerance = settings.atol;
  const auto result = with_stepper<System>(method, settings, [&](auto& stepper) {
    return simulate(system, stepper, x0, typename System::Mode{}, 0.0, t_end, options, log);
  });
  EXPECT_EQ(result.termination, Termination::completed) << method;
  return result;
}

template <class System>
std::vector<EventRecord> run_events(const System& system, typename System::State x0,
                                    const std::string& method, double rtol, double t_end) {
  EventLog log;
  run(system, x0, method, rtol, t_end, log);
  return log.records();
}

std::size_t count(const std::vector<EventRecord>& events, EventKind kind) {
  return static_cast<std::size_t>(
      std::count_if(events.begin(), events.end(), [&](const auto& e) { return e.kind == kind; }));
}

void expect_same_events(const std::vector<EventRecord>& expected,
                        const std::vector<EventRecord>& actual, double tolerance) {
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE("event " + std::to_string(i));
    ASSERT_EQ(expected[i].kind, actual[i].kind);
    ASSERT_EQ(expected[i].wall, actual[i].wall);
    EXPECT_NEAR(expected[i].t, actual[i].t, tolerance);
    EXPECT_NEAR(expected[i].qdot_after, actual[i].qdot_after, tolerance);
  }
}

// Against the closed-form flow of the built-in oscillator (the `exact`
// method: free flight solved in closed form, impacts located on it): 60
// forcing periods of periodic impacting motion, and a low stop where the
// impacts chatter, accumulate, and the mass rests on the stop until the
// forcing pulls it away.
TEST(ModelFileTaylor, LinearImpactGivesTheClosedFormEvents) {
  const auto model = compiled_example("linear_impact_model.toml");
  ASSERT_TRUE(model->series_refusal.empty()) << model->series_refusal;
  {
    const ModelSystem<2> from_file(model, model_parameter_values(*model, {}));
    const LinearImpact built_in{LinearImpactParameters{}};
    const double t_end = 60 * 2 * std::numbers::pi / 2.0;
    const auto exact = run_events(built_in, {0.0, 0.0}, "exact", 1e-12, t_end);
    const auto series = run_events(from_file, {0.0, 0.0}, "taylor", 1e-12, t_end);
    EXPECT_GT(count(exact, EventKind::impact), 50u);
    expect_same_events(exact, series, 1e-9);
  }
  {
    LinearImpactParameters p;
    p.sigma = 0.0;
    p.r = 0.5;
    p.omega = 0.5;
    const ModelSystem<2> from_file(model,
                                   model_parameter_values(*model, {{"sigma", 0.0}, {"r", 0.5}, {"omega", 0.5}}));
    const LinearImpact built_in{p};
    const double t_end = 20 * 2 * std::numbers::pi / p.omega;
    const auto exact = run_events(built_in, {-0.5, 0.0}, "exact", 1e-12, t_end);
    const auto series = run_events(from_file, {-0.5, 0.0}, "taylor", 1e-12, t_end);
    EXPECT_GT(count(exact, EventKind::accumulation), 5u);
    EXPECT_GT(count(exact, EventKind::contact_end), 5u);
    expect_same_events(exact, series, 1e-8);
  }
}

// A cubic spring (x^3, a power) has no closed form: against rkf78 at a
// tolerance a hundred times tighter, an independent integrator.
TEST(ModelFileTaylor, DuffingWithAStopGivesATightRungeKuttaRunsEvents) {
  const auto model = compiled_example("duffing_stop.toml");
  ASSERT_TRUE(model->series_refusal.empty()) << model->series_refusal;
  const ModelSystem<2> system(model, model_parameter_values(*model, {}));
  const double t_end = 40 * 2 * std::numbers::pi / system.forcing_frequency();
  const auto reference = run_events(system, {0.0, 0.0}, "rkf78", 1e-14, t_end);
  const auto series = run_events(system, {0.0, 0.0}, "taylor", 1e-12, t_end);
  EXPECT_GT(count(reference, EventKind::impact), 20u);
  expect_same_events(reference, series, 1e-8);
}

const std::string model_head = R"([model]
states = ["x", "v"]
forcing_frequency = "omega"
[model.parameters]
omega = 1.0
[model.rhs]
x = "v"
)";

// Each operation without a series is named, with the function it sits in;
// the others have series.
TEST(ModelFileTaylor, AnOperationWithoutASeriesIsNamed) {
  struct Case {
    std::string v_equation;
    std::string refusal;  // a part of series_refusal; empty: none
  };
  for (const Case& c : std::vector<Case>{
           {"-x^3 + cos(omega*t) - abs(v)*v + sin(x)/(1 + x^2)", ""},
           {"-x^16 - x^(-2) - x^17 - abs(x)^1.5", ""},
           {"-exp(x) - log(2 + x^2) - sqrt(1 + x^2) - tan(x)", ""},
           {"-sinh(x) - cosh(v) - tanh(x)", ""},
           {"-atan(x)", "the free right-hand side: it uses atan"},
           {"-asin(x/2)", "it uses asin"},
           {"-acos(x/2)", "it uses acos"},
           {"-atan2(x, v)", "it uses atan2"},
           {"-x^omega", "whose exponent is not a constant"}}) {
    SCOPED_TRACE(c.v_equation);
    const auto model = compiled_text(model_head + "v = \"" + c.v_equation + "\"\n");
    if (c.refusal.empty()) {
      EXPECT_EQ(model->series_refusal, "");
      EXPECT_FALSE(model->free_rhs_series.empty());
    } else {
      EXPECT_NE(model->series_refusal.find(c.refusal), std::string::npos) << model->series_refusal;
      EXPECT_TRUE(model->free_rhs_series.empty());
    }
  }
  // a witness too
  const auto walled = compiled_text(model_head + "v = \"-x\"\n[[model.walls]]\n"
                                                 "witness = \"1 - atan(x)\"\n"
                                                 "direction = \"falling\"\n"
                                                 "reset = { velocity = \"v\", restitution = \"0.5\", "
                                                 "position = \"x\" }\n");
  EXPECT_NE(walled->series_refusal.find("the gap to wall"), std::string::npos)
      << walled->series_refusal;
}

const std::string nonlinear_model = R"toml([model]
states = ["x", "v"]
forcing_frequency = "omega"
[model.parameters]
omega = 1.3
[model.rhs]
x = "v"
v = "1.5*cos(omega*t) - 0.1*v - x*sqrt(1 + x^2) - 0.2*tanh(3*v) + 0.05*exp(-x^2) + 0.1*(1 + x^2)^0.75 - 0.05*log(2 + v^2) + 0.02*tan(0.3*x)"
[[model.walls]]
witness = "0.8 - x"
direction = "falling"
reset = { velocity = "v", restitution = "0.7", position = "x" }
)toml";

// Every function with a series at once (√, tanh, exp, log, a real power,
// tan), against rkf78 at a tolerance a hundred times tighter: the events,
// and the fundamental matrix of the variational equations over impacts,
// whose Taylor run differentiates the series programs as dual numbers
// while rkf78 runs the model's compiled Jacobian: two independent
// derivations of the same matrix.
TEST(ModelFileTaylor, EveryFunctionWithASeriesGivesARungeKuttaRunsEventsAndJacobian) {
  const auto model = compiled_text(nonlinear_model);
  ASSERT_TRUE(model->series_refusal.empty()) << model->series_refusal;
  const ModelSystem<2> system(model, model_parameter_values(*model, {}));
  const double t_end = 30 * 2 * std::numbers::pi / system.forcing_frequency();
  const auto reference = run_events(system, {0.0, 0.0}, "rkf78", 1e-14, t_end);
  const auto series = run_events(system, {0.0, 0.0}, "taylor", 1e-12, t_end);
  EXPECT_GT(count(reference, EventKind::impact), 10u);
  expect_same_events(reference, series, 1e-8);

  using Tangent = Variational<ModelSystem<2>>;
  const Tangent tangent(system);
  const auto fundamental = [&](const std::string& method, double rtol) {
    EventLog log;
    const auto result = run(tangent, tangent.start({0.1, 0.0}, ModelSystem<2>::free_mode), method,
                            rtol, 4 * 2 * std::numbers::pi / 1.3, log);
    EXPECT_GT(count(log.records(), EventKind::impact), 1u) << method;
    return Tangent::fundamental_matrix(result.state);
  };
  const auto expected = fundamental("rkf78", 1e-14);
  const auto actual = fundamental("taylor", 1e-12);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j)
      EXPECT_NEAR(actual[i][j], expected[i][j], 1e-7 * (1.0 + std::fabs(expected[i][j])))
          << i << ", " << j;
}

// Over doubles, a series program computes what the compiled kernel does, to
// a few ulps (an integer power is a product here, pow in C).
TEST(ModelFileTaylor, ProgramsOverDoublesAreTheCompiledKernels) {
  const auto model = compiled_example("duffing_stop.toml");
  ASSERT_TRUE(model->compiled) << model->slow_path_reason;
  const ModelSystem<2> system(model, model_parameter_values(*model, {}));
  const std::vector<double>& p = system.parameters().values;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  for (int trial = 0; trial < 100; ++trial) {
    const std::array<double, 2> x{uniform(random), uniform(random)};
    const double t = 5.0 * uniform(random);
    double compiled[3], series[3];
    model->free_rhs(x.data(), t, p.data(), compiled);
    model->free_rhs_series.run(x.data(), t, p.data(), series);
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(series[i], compiled[i], 1e-14 * (1.0 + std::fabs(compiled[i])));
    model->gap[0](x.data(), t, p.data(), compiled);
    model->gap_series[0].run(x.data(), t, p.data(), series);
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(series[i], compiled[i], 1e-14 * (1.0 + std::fabs(compiled[i])));
    model->stick_force[0](x.data(), t, p.data(), compiled);
    model->stick_force_series[0].run(x.data(), t, p.data(), series);
    for (int i = 0; i < 2; ++i)
      EXPECT_NEAR(series[i], compiled[i], 1e-14 * (1.0 + std::fabs(compiled[i])));
  }
}

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
