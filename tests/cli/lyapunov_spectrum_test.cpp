// The Lyapunov spectrum from the command line, as a user runs it:
// * `poincare --lyapunov-spectrum` writes lyapunov.csv (a comment line with
//   the units, then t, lambda1..lambdaN, one row per averaged period, the
//   last row the result) and meta.json's lyapunov_spectrum with its error;
//   with `--lyapunov` too, its exponent is λ1 (one tangent run gives both;
//   tests/analysis/lyapunov_spectrum_test.cpp compares the two methods);
// * a ball that sticks to its table every period: -inf in lyapunov.csv, null
//   in meta.json (JSON has no infinities) with a note that says why;
// * the rigid pendulum resting on a wall every period: the two directions
//   the contact pins are -inf, the free spin's stays finite;
// * a 4-state model file (the impact damper): four exponents;
// * a 4-state model file with a sticking wall has no linearisation: exit 0
//   and a note, as the largest exponent does;
// * `sweep` and `basins` gain the columns lyapunov1..N, only when asked for;
//   a sweep stopped and resumed writes the same ones as a fresh sweep;
// * bad input: exit status 2 and one line naming the option and the value.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

const std::string examples =
    std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/";

nlohmann::json meta_of(const fs::path& folder) {
  return nlohmann::json::parse(slurp(folder / "meta.json"));
}

// a CSV field as the program wrote it ("-inf" included)
double number(const std::string& field) { return std::stod(field); }

TEST(LyapunovSpectrumCli, PoincareWritesTheSpectrumAndItsRunningEstimate) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "chaos";
  // ω = 2.6: a chaotic orbit of the linear impact oscillator
  const ProgramRun run = run_command_line(
      "poincare linear_impact --set omega=2.6 --points 300 --lyapunov --lyapunov-spectrum "
      "--quiet --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = meta_of(out);
  ASSERT_EQ(meta["lyapunov_spectrum"].size(), 2u);
  const double lambda1 = meta["lyapunov_spectrum"][0], lambda2 = meta["lyapunov_spectrum"][1];
  const double largest = meta["lyapunov"]["largest_exponent_per_time"];
  EXPECT_NEAR(lambda1, largest, 1e-10);
  EXPECT_GT(lambda1, 0.05);
  EXPECT_LT(lambda2, 0.0);
  for (const auto& error : meta["lyapunov_spectrum_error"]) {
    EXPECT_GE(error.get<double>(), 0.0);
    EXPECT_LT(error.get<double>(), 0.05);
  }
  EXPECT_EQ(meta["lyapunov_spectrum_info"]["unit"], "1/(scene time unit)");
  const auto files = meta["files"];
  EXPECT_NE(std::find(files.begin(), files.end(), "lyapunov.csv"), files.end());

  const std::vector<std::string> lines = split_lines(slurp(out / "lyapunov.csv"));
  ASSERT_EQ(lines.size(), 2u + 300u);
  EXPECT_TRUE(lines[0].starts_with("# running estimate")) << lines[0];
  EXPECT_NE(lines[0].find("1/(scene time unit)"), std::string::npos);
  EXPECT_EQ(lines[1], "t,lambda1,lambda2");
  const auto rows = read_csv(out / "lyapunov.csv");
  const auto& last = rows.back();
  ASSERT_EQ(last.size(), 3u);
  EXPECT_EQ(number(last[1]), lambda1);
  EXPECT_EQ(number(last[2]), lambda2);
  // the rows' times advance by one forcing period
  const double period = meta["forcing_period"];
  EXPECT_NEAR(number(rows[rows.size() - 1][0]) - number(rows[rows.size() - 2][0]), period,
              1e-9 * period * 300);
}

TEST(LyapunovSpectrumCli, StickingBallCollapsesToMinusInfinityNeverNaN) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "sticking";
  // r = 0.3, Γ ≈ 1.38: the ball chatters to rest on the table every period
  const ProgramRun run = run_command_line(
      "poincare bouncing_ball --set r=0.3 --set A=0.015 --points 40 --lyapunov-spectrum "
      "--quiet --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = meta_of(out);
  ASSERT_GT(meta["counts"]["contact_phases_recorded"].get<int>(), 10);
  ASSERT_EQ(meta["lyapunov_spectrum"].size(), 2u);
  EXPECT_TRUE(meta["lyapunov_spectrum"][0].is_null());
  EXPECT_TRUE(meta["lyapunov_spectrum"][1].is_null());
  EXPECT_NE(meta["lyapunov_spectrum_info"]["note"].get<std::string>().find("-inf"),
            std::string::npos);
  const auto rows = read_csv(out / "lyapunov.csv");
  EXPECT_EQ(rows.back()[1], "-inf");
  EXPECT_EQ(rows.back()[2], "-inf");
  EXPECT_EQ(slurp(out / "lyapunov.csv").find("nan"), std::string::npos);
}

TEST(LyapunovSpectrumCli, PendulumRestingOnAWallCollapsesItsSwingButNotItsSpin) {
  // the rigid bob with a free spin (tangent space θ, θ̇, spin): at V0 = 8 m/s
  // it comes to rest on a wall every period; the contact pins θ and θ̇ (their
  // directions collapse: −∞) and leaves the spin to its own decay (finite)
  const ScratchFolder scratch;
  const fs::path out = scratch / "rigid";
  const ProgramRun run = run_command_line(
      "poincare jin2003 --set model=rigid --set spin=free --set radius=0.02 --set V0=8 "
      "--points 60 --lyapunov --lyapunov-spectrum --quiet --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = meta_of(out);
  ASSERT_GT(meta["counts"]["contact_phases_recorded"].get<int>(), 10);
  ASSERT_EQ(meta["lyapunov_spectrum"].size(), 3u);
  ASSERT_TRUE(meta["lyapunov_spectrum"][0].is_number());
  EXPECT_NEAR(meta["lyapunov_spectrum"][0].get<double>(),
              meta["lyapunov"]["largest_exponent_per_time"].get<double>(), 1e-10);
  EXPECT_TRUE(meta["lyapunov_spectrum"][1].is_null());
  EXPECT_TRUE(meta["lyapunov_spectrum"][2].is_null());
  const auto rows = read_csv(out / "lyapunov.csv");
  EXPECT_TRUE(std::isfinite(number(rows.back()[1])));
  EXPECT_EQ(rows.back()[2], "-inf");
  EXPECT_EQ(rows.back()[3], "-inf");
}

TEST(LyapunovSpectrumCli, FourStateModelFileGivesFourExponents) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "damper";
  const ProgramRun run = run_impactlab(
      {"poincare", examples + "impact_damper.toml", "--set", "zeta=0.1", "--set", "omega=1.38",
       "--transient", "200", "--points", "100", "--lyapunov", "--lyapunov-spectrum", "--quiet",
       "--out", out.string()},
      {.environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()}, .limit_s = 120});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = meta_of(out);
  ASSERT_EQ(meta["lyapunov_spectrum"].size(), 4u);
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(meta["lyapunov_spectrum"][i].is_number()) << meta["lyapunov_spectrum"];
    if (i > 0) {
      EXPECT_LE(meta["lyapunov_spectrum"][i].get<double>(),
                meta["lyapunov_spectrum"][i - 1].get<double>() + 1e-3);
    }
  }
  EXPECT_NEAR(meta["lyapunov_spectrum"][0].get<double>(),
              meta["lyapunov"]["largest_exponent_per_time"].get<double>(), 1e-10);
  EXPECT_EQ(read_csv(out / "lyapunov.csv")[1].size(), 5u);
}

TEST(LyapunovSpectrumCli, ModelWithoutLinearisationGetsANoteAsTheLargestExponentDoes) {
  const ScratchFolder scratch;
  // a 4-state model whose wall sticks: its contact phases have no linearisation
  const fs::path file = scratch / "sticking_damper.toml";
  {
    std::ofstream written(file);
    written << R"toml(name = "two_masses_sticking"
description = "two uncoupled masses, one with a sticking stop (test)"

[initial]
x = 0.0
x_dot = 0.0
u = 0.0
u_dot = 0.0

[model]
states = ["x", "x_dot", "u", "u_dot"]
forcing_frequency = "omega"

[model.parameters]
A     = { default = 1.0 }
omega = { default = 2.0, min = 0.0, min_open = true }
sigma = { default = 0.2 }
r     = { default = 0.8, min = 0.0, max = 1.0 }

[model.rhs]
x = "x_dot"
x_dot = "A*cos(omega*t) - 0.1*x_dot - x"
u = "u_dot"
u_dot = "-0.2*u_dot - u"

[[model.walls]]
name = "stop"
side = 1
witness = "sigma - x"
direction = "falling"
reset = { velocity = "x_dot", restitution = "r", position = "x" }
sticking = { rhs = { x = "0", x_dot = "0", u = "u_dot", u_dot = "-0.2*u_dot - u" }, state = { x = "sigma", x_dot = "0", u = "u", u_dot = "u_dot" }, force = "A*cos(omega*t) - sigma" }
)toml";
  }
  const fs::path out = scratch / "out";
  const ProgramRun run = run_impactlab(
      {"poincare", file.string(), "--points", "20", "--lyapunov", "--lyapunov-spectrum",
       "--quiet", "--out", out.string()},
      {.environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()}, .limit_s = 120});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = meta_of(out);
  EXPECT_TRUE(meta["lyapunov_spectrum"].is_null());
  const std::string note = meta["lyapunov_spectrum_info"]["note"];
  EXPECT_NE(note.find("sticking"), std::string::npos) << note;
  EXPECT_EQ(note, meta["lyapunov"]["note"].get<std::string>());
}

TEST(LyapunovSpectrumCli, SweepAndBasinsGainOneColumnPerExponent) {
  const ScratchFolder scratch;
  {
    const ProgramRun run = run_command_line(
        "sweep linear_impact --param omega=2.5:2.7:3 --points 60 --lyapunov "
        "--lyapunov-spectrum --quiet --out " + (scratch / "sweep").string());
    ASSERT_EQ(run.status, 0) << run.err;
    const auto rows = read_csv(scratch / "sweep" / "summary.csv");
    ASSERT_EQ(rows.size(), 4u);
    const auto& header = rows[0];
    ASSERT_EQ(header[header.size() - 2], "lyapunov1");
    ASSERT_EQ(header.back(), "lyapunov2");
    const auto largest = std::find(header.begin(), header.end(), "lyapunov") - header.begin();
    for (std::size_t row = 1; row < rows.size(); ++row)
      EXPECT_NEAR(number(rows[row][header.size() - 2]), number(rows[row][largest]), 1e-10);
  }
  {
    const ProgramRun run = run_command_line(
        "sweep linear_impact --param omega=2.5:2.7:3 --points 20 --quiet --out " +
        (scratch / "plain").string());
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(slurp(scratch / "plain" / "summary.csv").find("lyapunov1"), std::string::npos);
  }
  {
    const ProgramRun run = run_command_line(
        "basins linear_impact --x omega=2.5:2.6:2 --y initial.x=0:0.1:2 --points 30 "
        "--lyapunov-spectrum --quiet --out " + (scratch / "basins").string());
    ASSERT_EQ(run.status, 0) << run.err;
    const auto rows = read_csv(scratch / "basins" / "basins.csv");
    ASSERT_EQ(rows.size(), 5u);
    EXPECT_EQ(rows[0][rows[0].size() - 2], "lyapunov1");
    EXPECT_EQ(rows[0].back(), "lyapunov2");
    for (std::size_t row = 1; row < rows.size(); ++row)
      EXPECT_TRUE(std::isfinite(number(rows[row].back()))) << row;
  }
}

TEST(LyapunovSpectrumCli, ResumedSweepWritesTheSameSpectrum) {
  // the checkpoint keeps each point's exponents (-inf and nan as text)
  const ScratchFolder scratch;
  const std::string sweep =
      "sweep linear_impact --param omega=2.5:2.7:6 --chunks 3 --lyapunov-spectrum --points 30 "
      "--quiet --out ";
  const ProgramRun stopped = run_command_line(sweep + (scratch / "a").string() + " --stop-after 2");
  ASSERT_EQ(stopped.status, 3) << stopped.err;
  const ProgramRun resumed = run_command_line(sweep + (scratch / "a").string() + " --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  const ProgramRun fresh = run_command_line(sweep + (scratch / "b").string());
  ASSERT_EQ(fresh.status, 0) << fresh.err;
  const std::string summary = slurp(scratch / "a" / "summary.csv");
  EXPECT_NE(summary.find("lyapunov2"), std::string::npos);
  EXPECT_EQ(summary, slurp(scratch / "b" / "summary.csv"));
}

TEST(LyapunovSpectrumCli, BadValueIsRefusedNamingTheOption) {
  const ProgramRun run = run_command_line("poincare linear_impact --lyapunov-spectrum=maybe");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("--lyapunov-spectrum"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("maybe"), std::string::npos) << run.err;
  // a command that has no spectrum
  EXPECT_TRUE(refused_naming(run_command_line("periodic linear_impact --lyapunov-spectrum"),
                             "--lyapunov-spectrum"));
}

}  // namespace
