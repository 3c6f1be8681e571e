// Regression tests of security and honesty, through the program as a user
// runs it: no shell injection through a path; every numeric option rejects
// NaN, infinities and negative counts; runs whose time
// cannot advance or whose state stops being finite end with exit 3 and a
// typed termination, never "completed"; runs past the resource limits are
// refused up front; library errors never come out as exit 1; every error is
// one line under 200 characters.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab::testing;

// The promise for bad input: exit 2, one line on stderr under 200 characters
// whose subject is `key`, and that shows `shown` too.
void expect_bad_input(const ProgramRun& run, const std::string& key,
                      const std::string& shown = {}) {
  EXPECT_FALSE(run.timed_out);
  EXPECT_EQ(run.signal, 0);
  EXPECT_TRUE(refused_naming(run, key));
  EXPECT_LT(run.err.size(), 200u) << run.err;
  EXPECT_NE(run.err.find(shown), std::string::npos) << run.err;
}

// The promise for a run stopped by a diagnostic: exit 3, the typed reason on
// stderr, and no output that says "completed".
void expect_stopped(const ProgramRun& run, const std::filesystem::path& out,
                    const std::string& reason) {
  EXPECT_FALSE(run.timed_out);
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find(reason), std::string::npos) << run.err;
  if (std::filesystem::exists(out / "meta.json")) {
    const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
    const std::string termination = meta.contains("run") ? meta["run"]["termination"]
                                                         : meta["termination"];
    EXPECT_EQ(termination, reason);
  }
}

TEST(ShellInjection, HostileOutDirectoryIsDataNotShellText) {
  const ScratchFolder dir;
  const std::string hostile = "d';touch INJECTED;'";
  const ProgramRun run =
      run_impactlab({"compare", "jin2003", "--periods", "1", "--quiet", "--out", hostile},
                    {.directory = dir.path(), .limit_s = 120});
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "INJECTED"));
  EXPECT_FALSE(std::filesystem::exists(dir / hostile / "INJECTED"));
  // the path was taken literally: the data are in the directory of that name
  EXPECT_TRUE(std::filesystem::exists(dir / hostile / "compare.json"));
}

struct BadOption {
  std::string name;
  std::vector<std::string> arguments;
  std::string key;         // the subject of the one line
  std::string shown = {};  // what else the line must show
};

class BadOptions : public ::testing::TestWithParam<BadOption> {};

TEST_P(BadOptions, ExitTwoWithOneShortLineNamingTheOption) {
  const ScratchFolder dir;
  const ProgramRun run =
      run_impactlab(GetParam().arguments, {.directory = dir.path(), .limit_s = 60});
  expect_bad_input(run, GetParam().key, GetParam().shown);
  // nothing written: no output directory
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

// 100 000 characters: one argument may hold at most 128 KiB (Linux's
// MAX_ARG_STRLEN), so a megabyte cannot be passed on a command line at all
const std::string long_value(100000, '7');

INSTANTIATE_TEST_SUITE_P(
    NonFiniteAndNegative, BadOptions,
    ::testing::Values(
        BadOption{"simulate_t_end_nan", {"simulate", "jin2003", "--t-end", "nan"}, "--t-end"},
        BadOption{"simulate_t_end_inf", {"simulate", "jin2003", "--t-end", "inf"}, "--t-end"},
        BadOption{"simulate_periods_nan", {"simulate", "jin2003", "--periods", "nan"}, "--periods"},
        BadOption{"simulate_periods_inf", {"simulate", "jin2003", "--periods", "-inf"}, "--periods"},
        BadOption{"simulate_sample_nan", {"simulate", "jin2003", "--sample", "nan"}, "--sample"},
        BadOption{"simulate_set_nan", {"simulate", "jin2003", "--set", "omega=nan"}, "omega"},
        BadOption{"simulate_set_inf", {"simulate", "jin2003", "--set", "V0=inf"}, "V0"},
        BadOption{"poincare_transient_nan", {"poincare", "jin2003", "--transient", "nan"},
                  "--transient"},
        BadOption{"poincare_transient_inf", {"poincare", "jin2003", "--transient", "inf"},
                  "--transient"},
        BadOption{"poincare_transient_impacts_negative",
                  {"poincare", "jin2003", "--transient-impacts", "-1"}, "--transient-impacts"},
        BadOption{"poincare_points_negative", {"poincare", "jin2003", "--points", "-1"},
                  "--points"},
        BadOption{"sweep_transient_nan",
                  {"sweep", "jin2003", "--param", "omega=1:2:3", "--transient", "nan"},
                  "--transient"},
        BadOption{"sweep_period_tol_nan",
                  {"sweep", "jin2003", "--param", "omega=1:2:3", "--period-tol", "nan"},
                  "--period-tol"},
        BadOption{"periodic_phase_nan", {"periodic", "jin2003", "--period", "2", "--phase", "nan"},
                  "--phase"},
        BadOption{"periodic_tolerance_nan", {"periodic", "jin2003", "--tolerance", "nan"},
                  "--tolerance"},
        BadOption{"periodic_transient_inf", {"periodic", "jin2003", "--transient", "inf"},
                  "--transient"},
        BadOption{"spectrum_transient_nan", {"spectrum", "jin2003", "--transient", "nan"},
                  "--transient"},
        // --t-end is an absolute end time: 0 is not after t0 = 0, not "not given"
        BadOption{"simulate_t_end_zero", {"simulate", "jin2003", "--t-end", "0"}, "--t-end"},
        // messages: one line (a newline in a value is escaped), long values elided
        BadOption{"set_value_with_newline", {"simulate", "jin2003", "--set", "omega=1\n2"},
                  "omega", "omega = 1\\n2"},
        BadOption{"set_value_100k_characters", {"simulate", "jin2003", "--set", "omega=x" + long_value},
                  "omega"},
        BadOption{"scene_name_100k_characters", {"simulate", long_value}, "scene"},
        // the span comes from --periods (default) and omega: the message names
        // omega, never --t-end, which the user did not give
        BadOption{"omega_tiny_names_omega",
                  {"simulate", "linear_impact", "--set", "omega=1e-308"}, "omega"},
        // resource limits, refused up front with the estimate and how to raise them
        // (the subject: the option that sets how long the run is, or how
        // many rows it writes)
        BadOption{"periods_huge", {"simulate", "jin2003", "--periods", "1e308"}, "--periods",
                  "limits.max_steps"},
        BadOption{"sample_tiny", {"simulate", "jin2003", "--sample", "1e-308"}, "--sample",
                  "limits.max_rows"},
        BadOption{"sample_a_billion_rows",
                  {"simulate", "jin2003", "--sample", "1e-9", "--periods", "1"}, "--sample",
                  "limits.max_rows"},
        BadOption{"pendulum_g_huge", {"simulate", "jin2003", "--set", "g=1e20"}, "--periods",
                  "limits.max_steps"},
        BadOption{"pendulum_m_tiny", {"simulate", "jin2003", "--set", "m=1e-12"}, "--periods",
                  "limits.max_steps"},
        BadOption{"pendulum_d_huge", {"simulate", "jin2003", "--set", "d=1e12"}, "--periods",
                  "limits.max_steps"},
        // these ran to "completed" with NaN states: the damping time m l^2/d
        // (1e-200 s, 1e-200 s) sizes them up front now
        BadOption{"pendulum_m_1em200", {"simulate", "jin2003", "--set", "m=1e-200"},
                  "--periods", "limits.max_steps"},
        BadOption{"pendulum_d_1e200", {"simulate", "jin2003", "--set", "d=1e200"}, "--periods",
                  "limits.max_steps"},
        // a moment of inertia m l^2 that overflows: exit 0 "completed" with an
        // infinite impulse at t0 and no final time before
        BadOption{"pendulum_l_1e200",
                  {"simulate", "jin2003", "--set", "l=1e200", "--periods", "3"}, "l",
                  "moment of inertia"},
        BadOption{"pendulum_m_huge_l_large",
                  {"simulate", "jin2003", "--set", "m=1e300", "--set", "l=1e5"}, "m",
                  "moment of inertia"},
        // a sweep's or basins map's grid sized up front against limits.max_rows:
        // the 2D grid of 10^14 points reached 9.4 GB in 30 s laying out its tasks
        BadOption{"sweep_grid_2d_huge",
                  {"sweep", "jin2003", "--param", "omega=5:9:10000000", "--param",
                   "V0=1:2:10000000"},
                  "--param", "limits.max_rows"},
        BadOption{"sweep_grid_1d_both_directions",
                  {"sweep", "jin2003", "--param", "omega=5:9:10000000", "--direction", "both"},
                  "--param", "limits.max_rows"},
        BadOption{"sweep_points_1d",
                  {"sweep", "jin2003", "--param", "omega=5:9:1000000"}, "--points",
                  "limits.max_rows"},
        BadOption{"basins_grid_huge",
                  {"basins", "jin2003", "--x", "initial.theta=-0.1:0.1:10000000", "--y",
                   "initial.theta_dot=-1:1:10000000"},
                  "--x/--y", "limits.max_rows"},
        // 5 periods (4.5 s) after t0 = 1e17 s round to t0 itself (a double's
        // resolution there is 16 s): refused up front, naming t0
        BadOption{"simulate_t0_1e17",
                  {"simulate", "jin2003", "--set", "t0=1e17", "--periods", "5"}, "t0",
                  "t0 = 1e+17"},
        BadOption{"poincare_transient_huge", {"poincare", "jin2003", "--transient", "1e9"},
                  "--transient"},
        BadOption{"periodic_omega_tiny", {"periodic", "linear_impact", "--set", "omega=1e-308"},
                  "omega"},
        BadOption{"poincare_omega_tiny",
                  {"poincare", "linear_impact", "--set", "omega=1e-308"}, "omega"}),
    [](const auto& info) { return info.param.name; });

// The library names an option by its own name (`transient`, `set`) and the
// command line spells it as its flag: each line as the program printed it
// when the library still wrote the flags itself.
struct SpelledLine {
  std::string name;
  std::vector<std::string> arguments;
  std::string line;  // stderr, without "impactlab: " and the newline
};

class LibraryMessagesSpellFlags : public ::testing::TestWithParam<SpelledLine> {};

TEST_P(LibraryMessagesSpellFlags, AsTheCommandLineWroteThem) {
  const ScratchFolder dir;
  std::vector<std::string> arguments = GetParam().arguments;
  arguments.insert(arguments.end(), {"--quiet", "--out", "o"});
  const ProgramRun run = run_impactlab(arguments, {.directory = dir.path(), .limit_s = 120});
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_EQ(run.err, "impactlab: " + GetParam().line + "\n");
}

const std::string max_steps_hint = " (raise it with --set limits.max_steps=N)";

INSTANTIATE_TEST_SUITE_P(
    SectionSweepRunAndContinuation, LibraryMessagesSpellFlags,
    ::testing::Values(
        SpelledLine{"transient",
                    {"poincare", "jin2003", "--transient", "1e9"},
                    "--transient = 1000000000: needs at least 1.6e+10 steps, over "
                    "limits.max_steps = 100000000" + max_steps_hint},
        SpelledLine{"t_end",
                    {"simulate", "jin2003", "--t-end", "1e300"},
                    "--t-end = 1e+300: needs at least 1.78e+301 steps, over limits.max_steps = "
                    "100000000" + max_steps_hint},
        SpelledLine{"sample",
                    {"simulate", "jin2003", "--sample", "1e-308"},
                    "--sample = 1e-308: would write inf rows, over limits.max_rows = 10000000 "
                    "(raise it with --set limits.max_rows=N)"},
        SpelledLine{"param",
                    {"sweep", "jin2003", "--param", "model=0:1:5"},
                    "--param = model: not a numeric key of oscillator pendulum_walls"},
        SpelledLine{"misspelt_key",
                    {"simulate", "jin2003", "--set", "omegaa=3"},
                    "omegaa = 3: unknown key for oscillator pendulum_walls: did you mean omega? "
                    "(impactlab scenes lists every key of each scene)"},
        SpelledLine{"unbounded_range",
                    {"simulate", "jin2003", "--set", "d=-1"},
                    "d = -1: out of range [0, inf]"},
        SpelledLine{"param_three_times",
                    {"sweep", "jin2003", "--param", "omega=5:6:3", "--param", "V0=1:2:3",
                     "--param", "mu=0:1:2"},
                    "--param = mu=0:1:2: given 3 times; at most 2"},
        SpelledLine{"section",
                    {"continue", "jin2003", "--param", "omega=2:2.5", "--section", "impact:2"},
                    "--section = impact:2: the wall after impact: must be +1, -1 or 0 (any "
                    "wall)"}),
    [](const auto& info) { return info.param.name; });

TEST(BadOptions, TEndNeverNamedWhenNotGiven) {
  const ScratchFolder dir;
  const ProgramRun run = run_impactlab({"simulate", "linear_impact", "--set", "omega=1e-308"},
                                       {.directory = dir.path(), .limit_s = 60});
  EXPECT_EQ(run.err.find("--t-end"), std::string::npos) << run.err;
}

TEST(BadOptions, RaisedLimitLetsTheRunThrough) {
  // the same run as sample_a_billion_rows, shortened, with limits.max_rows raised
  const ScratchFolder dir;
  const ProgramRun refused =
      run_impactlab({"simulate", "jin2003", "--sample", "1e-5", "--t-end", "1", "--quiet", "--set",
                     "limits.max_rows=1e4", "--out", "o"},
                    {.directory = dir.path(), .limit_s = 60});
  expect_bad_input(refused, "--sample", "limits.max_rows");
  const ProgramRun allowed =
      run_impactlab({"simulate", "jin2003", "--sample", "1e-5", "--t-end", "1", "--quiet", "--set",
                     "limits.max_rows=2e5", "--out", "o"},
                    {.directory = dir.path(), .limit_s = 60});
  EXPECT_EQ(allowed.status, 0) << allowed.err;
}

struct StoppedCase {
  std::string name;
  std::vector<std::string> arguments;
  std::string reason;
};

class StoppedRuns : public ::testing::TestWithParam<StoppedCase> {};

TEST_P(StoppedRuns, ExitThreeWithTypedReasonNeverCompleted) {
  const ScratchFolder dir;
  std::vector<std::string> arguments = GetParam().arguments;
  arguments.insert(arguments.end(), {"--out", "o", "--quiet"});
  const ProgramRun run = run_impactlab(arguments, {.directory = dir.path(), .limit_s = 60});
  expect_stopped(run, dir / "o", GetParam().reason);
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
}

INSTANTIATE_TEST_SUITE_P(
    FrozenTimeAndNonFiniteStates, StoppedRuns,
    ::testing::Values(
        // time can no longer advance in a double at 1e17 s
        StoppedCase{"poincare_t0_1e17",
                    {"poincare", "jin2003", "--set", "t0=1e17", "--points", "5", "--transient", "0"},
                    "frozen_time"},
        StoppedCase{"periodic_t0_1e17",
                    {"periodic", "jin2003", "--period", "2", "--set", "t0=1e17", "--transient", "1"},
                    "frozen_time"},
        StoppedCase{"poincare_ball_t0_1e308",
                    {"poincare", "bouncing_ball", "--set", "t0=1e308"}, "frozen_time"},
        // states that overflow: stopped, not "completed" with NaN rows
        StoppedCase{"simulate_V0_1e308",
                    {"simulate", "jin2003", "--set", "V0=1e308", "--periods", "1"},
                    "non_finite_state"},
        StoppedCase{"simulate_ball_V0_huge",
                    // the height 1e308 m/s × t passes the largest double at t = 1.8 s:
                    // 20 periods (4.2 s); over one period (0.21 s) it stays finite
                    {"simulate", "bouncing_ball", "--set", "initial.y_dot=1e308", "--periods",
                     "20"},
                    "non_finite_state"}),
    [](const auto& info) { return info.param.name; });

// Boost.Math's toms748 "a and b out of order" reached the user as exit 1.
TEST(LibraryErrors, NeverExitOne) {
  for (const std::vector<std::string>& arguments :
       {std::vector<std::string>{"simulate", "jin2003", "--set", "V0=1e50", "--periods", "2"},
        std::vector<std::string>{"simulate", "jin2003", "--set", "t0=1e15", "--periods", "2"},
        std::vector<std::string>{"poincare", "jin2003", "--set", "t0=1e15", "--points", "3",
                                 "--transient", "1"}}) {
    const ScratchFolder dir;
    std::vector<std::string> with_out = arguments;
    with_out.insert(with_out.end(), {"--out", "o", "--quiet"});
    const ProgramRun run = run_impactlab(with_out, {.directory = dir.path(), .limit_s = 60});
    EXPECT_FALSE(run.timed_out) << arguments[3];
    EXPECT_TRUE(run.status == 0 || run.status == 2 || run.status == 3)
        << arguments[3] << ": exit " << run.status << ": " << run.err;
    EXPECT_LE(count_lines(run.err), 1) << run.err;
    EXPECT_EQ(run.err.find("toms748"), std::string::npos) << run.err;
  }
}


// A spectrum whose run stops early writes nothing, and leaves no output
// directory behind (its files are one run's, committed together).
TEST(RunAtomicity, StoppedSpectrumLeavesNoDirectory) {
  const ScratchFolder dir;
  const ProgramRun run =
      run_impactlab({"spectrum", "jin2003", "--set", "V0=1e308", "--quiet", "--out", "o"},
                    {.directory = dir.path(), .limit_s = 60});
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o"));
}

}  // namespace
