// Every function the expression parser accepts runs, compiled and on the
// interpreted evaluator, with its derivatives: a walk over the parser's own
// table (model_expression.hpp). GiNaC's derivative of abs holds conjugate(),
// which C lacks; the model's values are real, and the derivatives are written
// so (abs(asin(x)), abs(acos(x)), abs(log(v)), abs(atan2(x, v)) once failed
// with exit 1). Taylor runs a model whose operations all have series.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/oscillators/model_file/model_expression.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab;
using impactlab::testing::ScratchFolder;

std::string model_text(const std::string& v_equation) {
  return "[model]\nstates = [\"x\", \"v\"]\nforcing_frequency = \"1\"\n[model.rhs]\nx = \"v\"\nv = \"" +
         v_equation + "\"\n";
}

std::shared_ptr<const CompiledModel> compiled(const ScratchFolder& scratch, const std::string& v_equation,
                                              bool use_compiler) {
  const fs::path path = scratch / "model.toml";
  std::ofstream(path) << model_text(v_equation);
  CompileOptions options;
  options.cache_directory = (scratch / "cache").string();
  options.use_compiler = use_compiler;
  return compile_model(read_model_file(path.string()), options);
}

// the right-hand side and its Jacobian at one state
std::vector<double> rhs_and_jacobian(const CompiledModel& model) {
  const double x[2] = {0.3, 0.4};
  std::vector<double> out(6);
  model.free_rhs(x, 0.1, nullptr, out.data());
  model.free_jacobian(x, 0.1, nullptr, out.data() + 2);
  return out;
}

// the compiled code and the interpreter agree, and every value is finite
void expect_runs_both_ways(const std::string& v_equation) {
  SCOPED_TRACE(v_equation);
  const ScratchFolder scratch;
  const auto fast = compiled(scratch, v_equation, true);
  ASSERT_TRUE(fast->compiled) << fast->slow_path_reason;
  const auto slow = compiled(scratch, v_equation, false);
  const std::vector<double> expected = rhs_and_jacobian(*fast);
  const std::vector<double> actual = rhs_and_jacobian(*slow);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_TRUE(std::isfinite(expected[i])) << i;
    EXPECT_NEAR(actual[i], expected[i], 1e-14 * (1 + std::fabs(expected[i]))) << i;
  }
}

TEST(ModelFileFunctions, EveryFunctionOfTheParserRunsCompiledAndInterpreted) {
  // arguments inside every function's domain, whose conjugates GiNaC keeps
  const std::string first = "0.5 + 0.1*asin(x/2)";
  const std::string second = "0.7 + 0.1*acos(v/2)";
  std::size_t walked = 0;
  for (const ExpressionFunction& function : expression_functions()) {
    const std::string call = std::string(function.name) + "(" + first +
                             (function.arity == 2 ? ", " + second : std::string()) + ")";
    expect_runs_both_ways("-x + 0.1*" + call);
    expect_runs_both_ways("-x + 0.1*abs(" + call + ")");
    ++walked;
  }
  EXPECT_GE(walked, 15u);
}

TEST(ModelFileFunctions, AbsOfFunctionsWithoutARealConjugateRuns) {
  for (const char* term : {"abs(asin(x))", "abs(acos(x))", "abs(log(v))", "abs(atan2(x, v))"})
    expect_runs_both_ways(std::string("-x + ") + term);
}

// Taylor runs a model whose operations all have series, and `scenes` lists
// it; a model with one that has none (atan) is refused, naming the key and
// the operation. `exact` is never offered: a model has no closed-form flow.
TEST(ModelFileFunctions, TaylorRunsAModelWhoseOperationsHaveSeries) {
  const ScratchFolder scratch;
  const std::vector<std::string> environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()};
  const auto simulate_with_taylor = [&](const std::string& v_equation, const std::string& label) {
    const fs::path path = scratch / (label + ".toml");
    std::ofstream(path) << "[integrator]\nmethod = \"taylor\"\n" << model_text(v_equation);
    return impactlab::testing::run_impactlab({"simulate", path.string(), "--periods", "1",
                                              "--quiet", "--out", (scratch / label).string()},
                                             {.environment = environment});
  };
  const auto runs = simulate_with_taylor("-x + 0.1*sin(x)*abs(v) + 0.01*exp(-x^2)", "series");
  EXPECT_EQ(runs.status, 0) << runs.err;
  const auto refused = simulate_with_taylor("-x + 0.1*atan(x)", "no_series");
  EXPECT_TRUE(impactlab::testing::refused_naming(refused, "integrator.method")) << refused.err;
  EXPECT_NE(refused.err.find("uses atan"), std::string::npos) << refused.err;
  // `scenes` lists the methods a model file may use
  const fs::path plain = scratch / "plain.toml";
  std::ofstream(plain) << model_text("-x");
  const auto listed = impactlab::testing::run_impactlab({"scenes", plain.string()}, {.environment = environment});
  ASSERT_EQ(listed.status, 0) << listed.err;
  const std::string methods = listed.out.substr(listed.out.find("integrator.method"));
  const std::string line = methods.substr(0, methods.find('\n'));
  EXPECT_NE(line.find("dopri5"), std::string::npos) << line;
  EXPECT_NE(line.find("taylor"), std::string::npos) << line;
  EXPECT_EQ(line.find("exact"), std::string::npos) << line;
  const std::string classification = listed.out.substr(listed.out.find("integrator.classification_method"));
  const std::string classification_line = classification.substr(0, classification.find('\n'));
  EXPECT_NE(classification_line.find("dopri5"), std::string::npos) << classification_line;
  EXPECT_NE(classification_line.find("taylor"), std::string::npos) << classification_line;
  EXPECT_EQ(classification_line.find("exact"), std::string::npos) << classification_line;
}

}  // namespace
