// Small model files that once crashed the program (a stack overflow in the
// expression parser, in toml++ or in GiNaC's C printer) are refused with
// exit status 2 and one line FILE:LINE:COL naming the place: deep nesting of
// parentheses, functions, signs, powers and definitions
// (max_expression_nesting), a TOML header of 100,000 dotted parts, an
// exponent C cannot hold, a chain of definitions whose written-out size grows
// geometrically, a kernel too large to compile, an exact power too large to
// compute, a derivative GiNaC cannot form. Nesting within the bound
// still runs, and so does a chain whose code, each subexpression computed
// once, stays small.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

// lines 1-8; the second equation, on line 9, is each case's
const std::string head = R"([model]
states = ["x", "v"]
forcing_frequency = "omega"
[model.parameters]
omega = 1.0
k = 2.0
[model.rhs]
x = "v"
)";

std::string repeated(const std::string& part, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += part;
  return text;
}

// The run of `simulate` on the model file `text`, and the file's path.
struct Outcome {
  ProgramRun run;
  std::string path;
};

Outcome simulate_model(const ScratchFolder& scratch, const std::string& text) {
  const fs::path path = scratch / "model.toml";
  std::ofstream(path) << text;
  const std::vector<std::string> environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()};
  return {run_impactlab({"simulate", path.string(), "--periods", "1", "--quiet", "--out",
                         (scratch / "out").string()},
                        {.environment = environment, .limit_s = 120}),
          path.string()};
}

// exit 2, one line "impactlab: FILE:LINE:COL: ..." holding `message`; no output folder
void expect_refused_at(const ScratchFolder& scratch, const Outcome& outcome, const std::string& place,
                       const std::string& message) {
  EXPECT_EQ(outcome.run.signal, 0);
  EXPECT_EQ(outcome.run.status, 2) << outcome.run.err.substr(0, 300);
  EXPECT_EQ(count_lines(outcome.run.err), 1) << outcome.run.err.substr(0, 300);
  const std::string prefix = "impactlab: " + outcome.path + ":" + place + ": ";
  EXPECT_EQ(outcome.run.err.rfind(prefix, 0), 0u) << outcome.run.err.substr(0, 300);
  EXPECT_NE(outcome.run.err.find(message), std::string::npos) << outcome.run.err.substr(0, 300);
  EXPECT_FALSE(fs::exists(scratch / "out" / "events.csv"));
}

const std::string too_deep = "nested deeper than 100 levels";

TEST(ModelFileLimits, TwentyThousandParenthesesAreRefused) {
  const ScratchFolder scratch;
  const auto outcome =
      simulate_model(scratch, head + "v = \"" + repeated("(", 20000) + "x" + repeated(")", 20000) + "\"\n");
  // the 100th parenthesis opens level 101 (the expression starts at column 6)
  expect_refused_at(scratch, outcome, "9:106", too_deep);
}

TEST(ModelFileLimits, TwentyThousandNestedFunctionsAreRefused) {
  const ScratchFolder scratch;
  const auto outcome =
      simulate_model(scratch, head + "v = \"" + repeated("sin(", 20000) + "x" + repeated(")", 20000) + "\"\n");
  expect_refused_at(scratch, outcome, "9:406", too_deep);
}

TEST(ModelFileLimits, TwoMillionSignsAreRefused) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(scratch, head + "v = \"" + repeated("-", 2000000) + "x\"\n");
  expect_refused_at(scratch, outcome, "9:106", too_deep);
}

TEST(ModelFileLimits, TwentyThousandPowersAreRefused) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(scratch, head + "v = \"" + repeated("x^", 20000) + "2\"\n");
  expect_refused_at(scratch, outcome, "9:206", too_deep);
}

// each definition names the one before: the nesting adds up through them
TEST(ModelFileLimits, AChainOfTwentyThousandDefinitionsIsRefused) {
  const ScratchFolder scratch;
  std::string definitions = "[model.definitions]\nd0 = \"x\"\n";
  for (int k = 1; k < 20000; ++k)
    definitions += "d" + std::to_string(k) + " = \"d" + std::to_string(k - 1) + " + 1\"\n";
  const auto outcome = simulate_model(scratch, head + "v = \"d19999\"\n" + definitions);
  EXPECT_EQ(outcome.run.signal, 0);
  EXPECT_EQ(outcome.run.status, 2) << outcome.run.err.substr(0, 300);
  EXPECT_EQ(count_lines(outcome.run.err), 1) << outcome.run.err.substr(0, 300);
  EXPECT_NE(outcome.run.err.find(too_deep), std::string::npos) << outcome.run.err.substr(0, 300);
  EXPECT_NE(outcome.run.err.find("model.definitions.d"), std::string::npos) << outcome.run.err.substr(0, 300);
}

TEST(ModelFileLimits, ATableHeaderOfAHundredThousandPartsIsRefused) {
  const ScratchFolder scratch;
  const auto outcome =
      simulate_model(scratch, head + "v = \"-x\"\n[a" + repeated(".a", 99999) + "]\n");
  EXPECT_EQ(outcome.run.signal, 0);
  EXPECT_EQ(outcome.run.status, 2) << outcome.run.err.substr(0, 300);
  EXPECT_EQ(count_lines(outcome.run.err), 1) << outcome.run.err.substr(0, 300);
  EXPECT_NE(outcome.run.err.find("a key of more than 32 dotted parts"), std::string::npos)
      << outcome.run.err.substr(0, 300);
  EXPECT_NE(outcome.run.err.find("line 10"), std::string::npos) << outcome.run.err.substr(0, 300);
}

TEST(ModelFileLimits, AnExponentCCannotHoldIsRefused) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(
      scratch, head + "v = \"-x\"\n[[model.walls]]\nwitness = \"0.2 - x + v^(1e300)\"\n"
                      "direction = \"falling\"\nreset = { velocity = \"v\", restitution = \"0.8\" }\n");
  // the '^' of line 11 (the witness starts at column 12)
  expect_refused_at(scratch, outcome, "11:23", "an integer exponent beyond");
}

// dk = sin(d{k-1})*cos(d{k-1}) + d{k-1}, k = 1 ... levels: each definition
// names the one before three times, so that the expression written out
// grows threefold per level (its C source, written out, once grew tenfold
// per level, past 100 s and gigabytes at 7 levels).
std::string definition_chain(int levels) {
  std::string definitions = "[model.definitions]\nd0 = \"x\"\n";
  for (int k = 1; k <= levels; ++k) {
    const std::string before = "d" + std::to_string(k - 1);
    definitions += "d" + std::to_string(k) + " = \"sin(" + before + ")*cos(" + before + ") + " + before + "\"\n";
  }
  return definitions;
}

// Each subexpression is computed once in the generated code: ten levels (a
// quarter of a million terms written out) compile to an object of about
// 20 kB (under 100 kB is asserted).
TEST(ModelFileLimits, ADefinitionChainCompilesToCodeThatGrowsLinearly) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(scratch, head + "v = \"-x + 0.01*d10\"\n" + definition_chain(10));
  EXPECT_FALSE(outcome.run.timed_out);
  ASSERT_EQ(outcome.run.status, 0) << outcome.run.err.substr(0, 300);
  EXPECT_TRUE(fs::exists(scratch / "out" / "events.csv"));
  int objects = 0;
  for (const auto& entry : fs::directory_iterator(scratch / "cache")) {
    if (entry.path().extension() != ".so") continue;
    ++objects;
    EXPECT_LT(fs::file_size(entry.path()), 100000u) << entry.path();
  }
  EXPECT_EQ(objects, 1);
}

// Differentiation works on the expression written out: past a million terms
// it is refused, at the expression that names the chain, before any work.
TEST(ModelFileLimits, ADefinitionChainThatGrowsGeometricallyIsRefused) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(scratch, head + "v = \"-x + 0.01*d40\"\n" + definition_chain(40));
  EXPECT_FALSE(outcome.run.timed_out);
  // at the expression of v (line 9; it starts at column 6)
  expect_refused_at(scratch, outcome, "9:6", "grows to more than 1000000 terms");
}

// A product of 700 different factors is 700 terms written out, but each
// partial derivative is a sum of 700 products of 699 factors: its code is
// refused by size, not left to the compiler.
TEST(ModelFileLimits, AKernelOfTooManyOperationsIsRefused) {
  const ScratchFolder scratch;
  std::string product = "sin(x + 1)";
  for (int k = 2; k <= 700; ++k) product += "*sin(x + " + std::to_string(k) + ")";
  const auto outcome = simulate_model(scratch, head + "v = \"" + product + "\"\n");
  EXPECT_FALSE(outcome.run.timed_out);
  // at the [model.rhs] table
  expect_refused_at(scratch, outcome, "7:1", "takes more than 200000 operations");
}

// GiNaC raises exact numbers exactly: 1e308^1000 has a million binary
// digits, and that raised to the 1000th power once ran for minutes
TEST(ModelFileLimits, AnExactPowerTooLargeToComputeIsRefused) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(scratch, head + "v = \"((1e308*x)^1000)^1000\"\n");
  EXPECT_FALSE(outcome.run.timed_out);
  // the second '^' (the expression starts at column 6)
  expect_refused_at(scratch, outcome, "9:22", "a number raised to a power too large to compute exactly");
}

// d(0^v)/dv holds log(0): GiNaC refuses to form it, which was exit status 1
TEST(ModelFileLimits, ADerivativeGiNaCCannotFormIsRefused) {
  const ScratchFolder scratch;
  const auto outcome = simulate_model(scratch, head + "v = \"0^v\"\n");
  // at the [model.rhs] table
  expect_refused_at(scratch, outcome, "7:1", "its derivatives cannot be formed");
}

TEST(ModelFileLimits, NestingWithinTheBoundRuns) {
  const ScratchFolder scratch;
  std::string definitions = "[model.definitions]\nd0 = \"x\"\n";
  for (int k = 1; k < 20; ++k)
    definitions += "d" + std::to_string(k) + " = \"(d" + std::to_string(k - 1) + ")\"\n";
  const auto outcome = simulate_model(
      scratch, head + "v = \"-" + repeated("(", 40) + "d19" + repeated(")", 40) + "\"\n" + definitions);
  EXPECT_EQ(outcome.run.status, 0) << outcome.run.err;
  EXPECT_TRUE(fs::exists(scratch / "out" / "events.csv"));
}

}  // namespace
