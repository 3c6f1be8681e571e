// The `poincare`, `sweep` and `periodic` commands end to end: the output contract
// (columns, sidecar), serial, threaded and MPI sweeps giving byte-identical
// files, a sweep interrupted midway resuming without recomputing its finished
// points (and leaving no data file before it is complete), and bad input
// exiting with status 2 and one line naming the key and the value.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <impactlab/platform/run_program.hpp>
#include <impactlab/simulate/series_batch.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using impactlab::ProgramOutput;
using impactlab::run_program;
using namespace impactlab::testing;

std::vector<double> fields(const std::string& line) {
  std::vector<double> values;
  std::stringstream stream(line);
  for (std::string field; std::getline(stream, field, ',');)
    values.push_back(std::strtod(field.c_str(), nullptr));
  return values;
}

const std::string sweep_1d =
    "sweep jin2003 --param omega=6:8:24 --direction both --transient 30 --points 12 --quiet";
const std::string sweep_2d =
    "sweep jin2003 --param omega=6.5:7.5:6 --param V0=1:2:4 --transient 30 --points 12 --quiet";

TEST(Poincare, StroboscopicPointsAtTheForcingPhase) {
  const ScratchFolder scratch;
  const auto out = scratch / "strobe";
  const double phase = 1.0;
  const ProgramRun o = run_command_line(
      "poincare linear_impact --section strobe:1 --transient 20 --points 7 "
      "--quiet --out " +
      out.string());
  ASSERT_EQ(o.status, 0) << o.err;
  const auto rows = split_lines(slurp(out / "poincare.csv"));
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows[0], "k,t,q,qdot");
  const double omega = 2.0;  // the scene's
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto v = fields(rows[k]);
    // ωt ≡ phase (mod 2π), one period apart, after the 20-period transient
    const double turns = (omega * v[1] - phase) / (2.0 * std::numbers::pi);
    EXPECT_NEAR(turns, std::round(turns), 1e-9) << rows[k];
    EXPECT_GE(v[1], 20.0 * 2.0 * std::numbers::pi / omega);
  }
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  EXPECT_EQ(meta["counts"]["points"], 7);
  EXPECT_EQ(meta["scene"]["oscillator"], "linear_impact");
}

TEST(Poincare, ImpactMapPointsLieOnTheStop) {
  const ScratchFolder scratch;
  const auto out = scratch / "impact";
  const ProgramRun o = run_command_line(
      "poincare linear_impact --section impact:1 --transient-impacts 30 "
      "--points 9 --quiet --out " +
      out.string());
  ASSERT_EQ(o.status, 0) << o.err;
  const auto rows = split_lines(slurp(out / "poincare.csv"));
  ASSERT_EQ(rows.size(), 10u);
  EXPECT_EQ(rows[0], "k,t,q,qdot,wall,phase");
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto v = fields(rows[k]);
    EXPECT_NEAR(v[2], 0.2, 1e-9) << rows[k];  // x = σ
    EXPECT_GT(v[3], 0.0) << rows[k];           // moving into the stop
    EXPECT_EQ(v[4], 1.0);
    EXPECT_NEAR(v[5], std::fmod(2.0 * v[1], 2.0 * std::numbers::pi), 1e-9);
  }
}

TEST(Poincare, UserGivenSectionCrossesTheLevelInItsDirection) {
  const ScratchFolder scratch;
  for (const std::string direction : {"up", "down"}) {
    const auto out = scratch / ("crossing-" + direction);
    const ProgramRun o = run_command_line("poincare linear_impact --section q=-1.5:" + direction +
                          " --transient 20 --points 6 --quiet --out " + out.string());
    ASSERT_EQ(o.status, 0) << o.err;
    const auto rows = split_lines(slurp(out / "poincare.csv"));
    ASSERT_EQ(rows.size(), 7u);
    EXPECT_EQ(rows[0], "k,t,q,qdot,phase");
    for (std::size_t k = 1; k < rows.size(); ++k) {
      const auto v = fields(rows[k]);
      EXPECT_NEAR(v[2], -1.5, 1e-9) << rows[k];
      EXPECT_GT(direction == "up" ? v[3] : -v[3], 0.0) << rows[k];
    }
  }
}

// Model P through the section hook: the impact map of the right wall lies on
// the wall (θ = asin(b/l)) with the bob moving in, and the Lyapunov exponent
// is reported as not available (Model P has no Jacobians) rather than computed.
TEST(Poincare, PaperModelImpactMapWithoutLyapunov) {
  const ScratchFolder scratch;
  const auto out = scratch / "paper";
  const ProgramRun o = run_command_line(
      "poincare jin2003 --set model=paper --set V0=4.163 --section impact:1 "
      "--transient-impacts 20 --points 6 --lyapunov --quiet --out " +
      out.string());
  ASSERT_EQ(o.status, 0) << o.err;
  const auto rows = split_lines(slurp(out / "poincare.csv"));
  ASSERT_EQ(rows.size(), 7u);
  const double theta0 = std::asin(0.05 / 0.7);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto v = fields(rows[k]);
    EXPECT_NEAR(v[2], theta0, 1e-12) << rows[k];
    EXPECT_GT(v[3], 0.0) << rows[k];
  }
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  EXPECT_EQ(meta["scene"]["keys"]["model"]["value"], "paper");
  // no exponent (a number where there is one): null, the note says why
  EXPECT_TRUE(meta["lyapunov"]["largest_exponent_per_time"].is_null());
  EXPECT_FALSE(meta["lyapunov"]["note"].get<std::string>().empty());
}

// meta.json stores the exponent as a number (it was a string)
TEST(Poincare, TheLyapunovExponentIsANumberInMeta) {
  const ScratchFolder scratch;
  const auto out = scratch / "poincare";
  const ProgramRun run = run_impactlab(
      {"poincare", "jin2003", "--points", "20", "--lyapunov", "--quiet", "--out", out});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  ASSERT_TRUE(meta["lyapunov"]["largest_exponent_per_time"].is_number());
  EXPECT_LT(meta["lyapunov"]["largest_exponent_per_time"].get<double>(), 0.0);
}

// The rows of a CSV file whose `column` passes `test`; -1 where the file has
// no such column.
template <class Test>
int rows_where(const std::filesystem::path& csv, const std::string& column, Test test) {
  const auto rows = read_csv(csv);
  const auto& header = rows.front();
  const auto index =
      static_cast<std::size_t>(std::find(header.begin(), header.end(), column) - header.begin());
  if (index == header.size()) return -1;
  int passing = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) passing += test(rows[i][index]) ? 1 : 0;
  return passing;
}

// The largest distance of poincare.csv's points from the hanging rest
// (θ, θ̇) = (0, 0), an exact equilibrium of the pendulum whose pivot moves
// vertically.
double farthest_from_rest(const std::filesystem::path& csv) {
  double farthest = 0.0;
  const auto rows = read_csv(csv);
  for (std::size_t i = 1; i < rows.size(); ++i)
    farthest = std::max(farthest, std::hypot(std::stod(rows[i][2]), std::stod(rows[i][3])));
  return farthest;
}

// At ω = 5.5, V0 = 1 the pendulum decays onto the hanging rest, slowly: 100
// periods leave it 1e-2 away. The default transient runs until the points
// settle; an explicit --transient runs exactly that; a budget too short to
// settle says so.
TEST(Poincare, TheTransientRunsUntilTheDecayingRestHasSettled) {
  const ScratchFolder scratch;
  const std::string scene = "poincare jin2003 --set omega=5.5 --set V0=1 --quiet --out ";
  const ProgramRun settling = run_command_line(scene + (scratch / "settle").string());
  ASSERT_EQ(settling.status, 0) << settling.err;
  EXPECT_EQ(settling.err, "");
  const auto meta = nlohmann::json::parse(slurp(scratch / "settle" / "meta.json"));
  EXPECT_EQ(meta["transient"]["end"], "settled");
  EXPECT_GT(meta["transient"]["periods"].get<double>(), 100.0);
  EXPECT_EQ(meta["section"]["settling"]["max_periods"], 2000.0);
  EXPECT_LT(farthest_from_rest(scratch / "settle" / "poincare.csv"), 1e-6);

  const ProgramRun fixed =
      run_command_line(scene + (scratch / "fixed").string() + " --transient 100");
  ASSERT_EQ(fixed.status, 0) << fixed.err;
  const auto fixed_meta = nlohmann::json::parse(slurp(scratch / "fixed" / "meta.json"));
  EXPECT_EQ(fixed_meta["transient"]["end"], "fixed");
  EXPECT_EQ(fixed_meta["transient"]["periods"], 100.0);
  EXPECT_TRUE(fixed_meta["section"]["settling"].is_null());
  EXPECT_GT(farthest_from_rest(scratch / "fixed" / "poincare.csv"), 1e-4);

  const ProgramRun budget =
      run_command_line(scene + (scratch / "budget").string() + " --max-transient 150");
  ASSERT_EQ(budget.status, 0) << budget.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(scratch / "budget" / "meta.json"))["transient"]["end"],
            "not_settled");
  EXPECT_NE(budget.err.find("warning: the transient did not settle within max_transient = 150"),
            std::string::npos)
      << budget.err;

  EXPECT_TRUE(refused_naming(
      run_command_line(scene + (scratch / "both").string() + " --transient 100 --max-transient 300"),
      "--transient"));
}

// The settling transient watches its last window through dense output: a
// run whose points end the least transient as not_periodic (the chattering
// V0 = 4.163) has, bit for bit, the section points of --transient 100.
TEST(Poincare, AWindowWatchedLeavesTheTrajectoryAsItWas) {
  const ScratchFolder scratch;
  const std::string scene = "poincare jin2003 --set V0=4.163 --quiet --out ";
  ASSERT_EQ(run_command_line(scene + (scratch / "settle").string()).status, 0);
  ASSERT_EQ(run_command_line(scene + (scratch / "fixed").string() + " --transient 100").status, 0);
  const auto meta = nlohmann::json::parse(slurp(scratch / "settle" / "meta.json"));
  ASSERT_EQ(meta["transient"]["end"], "not_periodic");
  ASSERT_EQ(meta["transient"]["periods"], 100.0);
  EXPECT_EQ(slurp(scratch / "settle" / "poincare.csv"), slurp(scratch / "fixed" / "poincare.csv"));
}

// A sweep's points that did not settle within the budget are marked in
// summary.csv and counted in a warning, even with --quiet.
TEST(Sweep, PointsThatDidNotSettleAreMarkedAndCounted) {
  const ScratchFolder scratch;
  const auto out = scratch / "unsettled";
  const ProgramRun run = run_command_line(
      "sweep jin2003 --set V0=1 --param omega=5.45:5.55:3 --no-lyapunov --max-transient 150 "
      "--quiet --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const int unsettled = rows_where(out / "summary.csv", "transient_end",
                                   [](const std::string& end) { return end == "not_settled"; });
  ASSERT_GT(unsettled, 0);
  EXPECT_NE(run.err.find("warning: " + std::to_string(unsettled) +
                         " of 3 points did not settle within max_transient = 150"),
            std::string::npos)
      << run.err;
}

// `command` run, with `more` arguments, on the shipped Duffing oscillator
// without its wall's sticking table (the file's last section) at r = 0.2,
// σ = 0.1, where it chatters into no_progress at some F; the model cache is
// the scratch folder's own.
ProgramRun run_without_sticking(const ScratchFolder& scratch, const std::string& command,
                                const std::vector<std::string>& more) {
  std::string model = slurp(std::filesystem::path(IMPACTLAB_SOURCE_DIR) /
                            "oscillators/model_file/examples/duffing_stop.toml");
  model = model.substr(0, model.find("[model.walls.sticking]"));
  const auto scene = scratch / "no_sticking.toml";
  std::ofstream(scene) << model;
  std::vector<std::string> arguments = {command, scene.string(), "--set", "r=0.2", "--set",
                                        "sigma=0.1", "--quiet"};
  arguments.insert(arguments.end(), more.begin(), more.end());
  return run_impactlab(arguments, {.environment = {"IMPACTLAB_CACHE_DIR=" +
                                                   (scratch / "cache").string()},
                                   .limit_s = 120});
}

// A sweep whose points stop early says so, even with --quiet, and how many
// and why, as summary.csv records them.
TEST(Sweep, PointsThatStopEarlyAreCountedInAWarning) {
  const ScratchFolder scratch;
  const auto out = scratch / "sweep";
  const ProgramRun run = run_without_sticking(
      scratch, "sweep", {"--param", "F=0.2:3:20", "--no-lyapunov", "--out", out.string()});
  ASSERT_EQ(run.status, 0) << run.err;
  const int stopped = rows_where(out / "summary.csv", "termination",
                                 [](const std::string& end) { return end != "completed"; });
  ASSERT_GT(stopped, 0);
  EXPECT_NE(run.err.find("warning: " + std::to_string(stopped) +
                         " of 20 points stopped early (no_progress "),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("summary.csv"), std::string::npos) << run.err;
}

// A run that stops because impacts accumulate on a wall without a sticking
// table says which wall and what to add, on stderr and in meta.json
TEST(Simulate, ImpactsAccumulatingOnAWallWithoutStickingSayWhatToAdd) {
  const ScratchFolder scratch;
  const auto out = scratch / "run";
  const ProgramRun run = run_without_sticking(
      scratch, "simulate", {"--set", "F=2.5", "--periods", "50", "--out", out.string()});
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find("(no_progress)"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("impacts accumulate on wall stop (side +1)"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("[model.walls.sticking]"), std::string::npos) << run.err;
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  EXPECT_NE(meta["run"]["stop_advice"].get<std::string>().find("[model.walls.sticking]"),
            std::string::npos);
}

TEST(Sweep, OneDimensionalColumnsAndBothDirections) {
  const ScratchFolder scratch;
  const auto out = scratch / "columns";
  const ProgramRun o = run_command_line(sweep_1d + " --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.err;
  const auto rows = split_lines(slurp(out / "bifurcation.csv"));
  EXPECT_EQ(rows[0], "omega,k,t,q,qdot,wall,direction");
  EXPECT_EQ(rows.size(), 1u + 2u * 24u * 12u);  // both directions, 24 values, 12 points
  const auto summary = split_lines(slurp(out / "summary.csv"));
  EXPECT_EQ(summary.size(), 1u + 48u);
  EXPECT_EQ(summary[1].rfind("6,up,", 0), 0u) << summary[1];
  EXPECT_EQ(summary[25].rfind("8,down,", 0), 0u) << summary[25];
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  EXPECT_EQ(meta["counts"]["points"], 48);
  EXPECT_FALSE(fs::exists(out / "checkpoint-0.jsonl"));
}

// The share of impacts that stick, per point: the rigid pendulum at V0 = 2
// needs a friction of about 13.6 for its impacts to stick and 2 or more for
// any to (the cone condition solved by hand, tests/oscillators/
// rigid_pendulum_spin_test.cpp), so μ = 16 sticks at every impact and
// μ = 0.5 at none; Model N's impacts never stick.
TEST(Sweep, StickFractionIsTheShareOfImpactsFrictionStops) {
  const ScratchFolder scratch;
  const std::string grid = " --param mu=0.5:16:2 --transient 300 --points 4 --quiet --out ";
  const ProgramRun rigid = run_command_line(
      "sweep jin2003 --set model=rigid --set spin=free --set radius=0.02 --set V0=2" + grid +
      (scratch / "rigid").string());
  ASSERT_EQ(rigid.status, 0) << rigid.err;
  const auto rows = split_lines(slurp(scratch / "rigid" / "summary.csv"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(rows[0].ends_with(",points,stick_fraction,transient_periods,transient_end"))
      << rows[0];
  // stick_fraction, the third column from the end
  auto stick_fraction = [](const std::string& row) {
    const auto values = fields(row.substr(0, row.rfind(',')));
    return values[values.size() - 2];
  };
  EXPECT_EQ(stick_fraction(rows[1]), 0.0) << rows[1];
  EXPECT_EQ(stick_fraction(rows[2]), 1.0) << rows[2];
  const ProgramRun newton =
      run_command_line("sweep jin2003 --set V0=2" + grid + (scratch / "newton").string());
  ASSERT_EQ(newton.status, 0) << newton.err;
  for (const auto& row : split_lines(slurp(scratch / "newton" / "summary.csv")))
    if (row.rfind("mu", 0) != 0) {
      EXPECT_EQ(stick_fraction(row), 0.0) << row;
    }
}

TEST(Sweep, SerialAndThreadedRunsWriteIdenticalFiles) {
  const ScratchFolder scratch;
  const auto serial = scratch / "serial", threaded = scratch / "threaded";
  ASSERT_EQ(run_command_line(sweep_1d + " --chunks 3 --threads 1 --out " + serial.string()).status,
            0);
  ASSERT_EQ(
      run_command_line(sweep_1d + " --chunks 3 --threads 2 --out " + threaded.string()).status, 0);
  EXPECT_EQ(slurp(serial / "bifurcation.csv"), slurp(threaded / "bifurcation.csv"));
  EXPECT_EQ(slurp(serial / "summary.csv"), slurp(threaded / "summary.csv"));

  const auto serial_2d = scratch / "serial2d", threaded_2d = scratch / "threaded2d";
  ASSERT_EQ(run_command_line(sweep_2d + " --threads 1 --out " + serial_2d.string()).status, 0);
  ASSERT_EQ(run_command_line(sweep_2d + " --threads 2 --out " + threaded_2d.string()).status, 0);
  const std::string classes = slurp(serial_2d / "classes.csv");
  EXPECT_EQ(split_lines(classes)[0],
            "omega,V0,period,impacts_per_period,contact,lyapunov,termination,stick_fraction,"
            "transient_periods,transient_end");
  EXPECT_EQ(split_lines(classes).size(), 1u + 24u);
  EXPECT_EQ(classes, slurp(threaded_2d / "classes.csv"));
}

// Trajectories in the lanes of a batch (--batch on, the default with the
// Taylor stepper) are the scalar runs to the last bit
// (simulate/series_batch.hpp): a 1D sweep in chunks, a 2D map with its
// Lyapunov exponents and a basins grid write the same files either way, and
// meta.json says how many lanes ran.
TEST(Sweep, BatchOnAndOffWriteIdenticalFiles) {
  const ScratchFolder scratch;
  const auto batch_width = [](const fs::path& dir) {
    return nlohmann::json::parse(slurp(dir / "meta.json"))["run"]["batch_width"].get<int>();
  };
  const auto on_1d = scratch / "on1d", off_1d = scratch / "off1d";
  ASSERT_EQ(run_command_line(sweep_1d + " --chunks 6 --batch on --out " + on_1d.string()).status, 0);
  ASSERT_EQ(
      run_command_line(sweep_1d + " --chunks 6 --batch off --out " + off_1d.string()).status, 0);
  EXPECT_EQ(slurp(on_1d / "bifurcation.csv"), slurp(off_1d / "bifurcation.csv"));
  EXPECT_EQ(slurp(on_1d / "summary.csv"), slurp(off_1d / "summary.csv"));
  EXPECT_EQ(batch_width(on_1d), impactlab::default_batch_width);
  EXPECT_EQ(batch_width(off_1d), 1);

  const auto on_2d = scratch / "on2d", off_2d = scratch / "off2d";
  ASSERT_EQ(run_command_line(sweep_2d + " --threads 2 --batch on --out " + on_2d.string()).status, 0);
  ASSERT_EQ(run_command_line(sweep_2d + " --batch off --out " + off_2d.string()).status, 0);
  EXPECT_EQ(slurp(on_2d / "classes.csv"), slurp(off_2d / "classes.csv"));
  EXPECT_EQ(batch_width(on_2d), impactlab::default_batch_width);

  const std::string basins =
      "basins jin2003 --set V0=4.163 --x initial.theta=-0.04:0.04:5 "
      "--y initial.theta_dot=-0.5:0.5:4 --transient 20 --points 8 --quiet";
  const auto on_basins = scratch / "on_basins", off_basins = scratch / "off_basins";
  ASSERT_EQ(run_command_line(basins + " --batch on --out " + on_basins.string()).status, 0);
  ASSERT_EQ(run_command_line(basins + " --batch off --out " + off_basins.string()).status, 0);
  EXPECT_EQ(slurp(on_basins / "basins.csv"), slurp(off_basins / "basins.csv"));
  EXPECT_EQ(slurp(on_basins / "attractors.csv"), slurp(off_basins / "attractors.csv"));
  EXPECT_EQ(batch_width(on_basins), impactlab::default_batch_width);
  // on by default
  const auto default_basins = scratch / "default_basins";
  ASSERT_EQ(run_command_line(basins + " --out " + default_basins.string()).status, 0);
  EXPECT_EQ(batch_width(default_basins), impactlab::default_batch_width);

  // another stepper runs no batch
  const auto rk = scratch / "rk";
  ASSERT_EQ(run_command_line("sweep jin2003 --param omega=6:8:3 --transient 5 --points 4 --quiet "
                             "--set integrator.method=dopri5 --out " +
                             rk.string())
                .status,
            0);
  EXPECT_EQ(batch_width(rk), 1);
}

TEST(Sweep, MetaRecordsTheClassificationAndLyapunovIntegrators) {
  const ScratchFolder scratch;
  // a 2D map classifies at the scene's classification integrator (the
  // Lyapunov exponent at the scene's own); a 1D sweep and a 2D map with an
  // integrator key set stay at the scene's or the user's integrator throughout
  const auto map = scratch / "integrators_2d", set = scratch / "integrators_set",
             one = scratch / "integrators_1d";
  ASSERT_EQ(run_command_line(sweep_2d + " --out " + map.string()).status, 0);
  ASSERT_EQ(
      run_command_line(sweep_2d + " --set integrator.rtol=1e-11 --out " + set.string()).status, 0);
  ASSERT_EQ(
      run_command_line("sweep jin2003 --param omega=6:8:3 --transient 5 --points 4 --quiet --out " +
                       one.string())
          .status,
      0);
  const auto sweep_of = [](const fs::path& dir) {
    return nlohmann::json::parse(slurp(dir / "meta.json"))["sweep"];
  };
  const auto m = sweep_of(map), s = sweep_of(set), o = sweep_of(one);
  // the built-in jin2003 states no classification tolerance
  // (oscillators/pendulum_walls/jin2003.toml): its own integrator, and the note says why
  EXPECT_EQ(m["classification_integrator"]["method"], "taylor") << m.dump(1);
  EXPECT_EQ(m["classification_integrator"]["rtol"], 1e-12) << m.dump(1);
  EXPECT_NE(m["classification_integrator_note"].get<std::string>().find("states no classification"),
            std::string::npos)
      << m.dump(1);
  EXPECT_EQ(m["lyapunov_integrator"]["method"], "taylor");
  EXPECT_EQ(m["lyapunov_integrator"]["rtol"], 1e-12);
  EXPECT_EQ(s["classification_integrator"]["rtol"], 1e-11);
  EXPECT_EQ(s["lyapunov_integrator"]["rtol"], 1e-11);
  EXPECT_EQ(o["classification_integrator"]["rtol"], 1e-12);
  EXPECT_TRUE(o["lyapunov_integrator"].is_null());
}

// (the ranks run their tasks in batches; the serial run runs none)
TEST(Sweep, MpiRunWritesTheSameFileAsTheSerialRun) {
  if (!mpirun_found()) GTEST_SKIP() << "no mpirun";
  const ScratchFolder scratch;
  const auto serial = scratch / "mpi_serial", parallel = scratch / "mpi_parallel";
  ASSERT_EQ(run_command_line(sweep_2d + " --batch off --out " + serial.string()).status, 0);
  const ProgramRun o =
      run_command_line(sweep_2d + " --batch on --out " + parallel.string(), {.mpi_ranks = 2});
  if (o.err.find("built without MPI") != std::string::npos) GTEST_SKIP() << "built without MPI";
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_EQ(slurp(serial / "classes.csv"), slurp(parallel / "classes.csv"));
  const auto meta = nlohmann::json::parse(slurp(parallel / "meta.json"));
  EXPECT_EQ(meta["run"]["mpi_ranks"], 2);
}

TEST(Sweep, InterruptedSweepResumesWithoutRecomputingFinishedPoints) {
  const ScratchFolder scratch;
  const auto whole = scratch / "whole", resumed = scratch / "resumed";
  ASSERT_EQ(run_command_line(sweep_1d + " --out " + whole.string()).status, 0);
  // stopped after 10 new points: exit 3, a checkpoint, no data file
  const ProgramRun stopped =
      run_command_line(sweep_1d + " --stop-after 10 --out " + resumed.string());
  EXPECT_EQ(stopped.status, 3) << stopped.err;
  EXPECT_FALSE(fs::exists(resumed / "bifurcation.csv"));
  EXPECT_FALSE(fs::exists(resumed / "meta.json"));
  EXPECT_EQ(split_lines(slurp(resumed / "checkpoint-0.jsonl")).size(), 1u + 10u);
  // a different sweep in the same directory does not reuse them
  const ProgramRun other = run_command_line(
      "sweep jin2003 --param omega=6:8:5 --transient 30 --points 12 "
      "--quiet --stop-after 1 --resume --out " +
      resumed.string());
  EXPECT_EQ(other.status, 3);
  ASSERT_EQ(run_command_line(sweep_1d + " --stop-after 10 --out " + resumed.string()).status, 3);
  // resumed: 10 points reused, the rest computed, the same file as one whole run
  const ProgramRun finished = run_command_line(sweep_1d + " --resume --out " + resumed.string());
  ASSERT_EQ(finished.status, 0) << finished.err;
  const auto meta = nlohmann::json::parse(slurp(resumed / "meta.json"));
  EXPECT_EQ(meta["run"]["points_reused_from_checkpoint"], 10);
  EXPECT_EQ(slurp(whole / "bifurcation.csv"), slurp(resumed / "bifurcation.csv"));
  EXPECT_EQ(slurp(whole / "summary.csv"), slurp(resumed / "summary.csv"));
}

// Checkpoint lines carry a checksum: an edited line ("period":7 in place of
// the computed period) changed classes.csv without a warning; it is refused
// now, naming the file and the line, and nothing is written.
TEST(Sweep, EditedCheckpointLineIsRefused) {
  const ScratchFolder scratch;
  const auto dir = scratch / "edited";
  ASSERT_EQ(run_command_line(sweep_1d + " --stop-after 4 --out " + dir.string()).status, 3);
  const fs::path checkpoint = dir / "checkpoint-0.jsonl";
  std::vector<std::string> lines = split_lines(slurp(checkpoint));
  ASSERT_EQ(lines.size(), 5u);
  const std::size_t period = lines[2].find("\"period\":");
  ASSERT_NE(period, std::string::npos) << lines[2];
  const char edited_period = lines[2][period + 9] == '7' ? '8' : '7';
  lines[2][period + 9] = edited_period;
  std::ofstream edited(checkpoint, std::ios::trunc);
  for (const auto& line : lines) edited << line << '\n';
  edited.close();
  const ProgramRun resumed = run_command_line(sweep_1d + " --resume --out " + dir.string());
  EXPECT_EQ(resumed.status, 2) << resumed.err;
  EXPECT_EQ(count_lines(resumed.err), 1) << resumed.err;
  EXPECT_NE(resumed.err.find("checkpoint-0.jsonl:3"), std::string::npos) << resumed.err;
  EXPECT_NE(resumed.err.find("checksum"), std::string::npos) << resumed.err;
  EXPECT_FALSE(fs::exists(dir / "bifurcation.csv"));
  EXPECT_FALSE(fs::exists(dir / "meta.json"));
}

TEST(Sweep, KilledSweepLeavesNoDataFileAndResumes) {
  const ScratchFolder scratch;
  const std::string sweep = "sweep jin2003 --param omega=5:9:200 --direction both --transient 50 "
                            "--points 20 --quiet";
  const auto whole = scratch / "kill_whole", killed = scratch / "killed";
  ASSERT_EQ(run_command_line(sweep + " --out " + whole.string()).status, 0);
  // SIGKILL once the checkpoint holds a few points
  const fs::path checkpoint = killed / "checkpoint-0.jsonl";
  run_command_line(sweep + " --out " + killed.string(),
                   {.kill_when = [&] { return count_lines(slurp(checkpoint)) >= 6; }});
  if (fs::exists(killed / "bifurcation.csv")) GTEST_SKIP() << "the sweep finished before the kill";
  EXPECT_FALSE(fs::exists(killed / "summary.csv"));
  EXPECT_FALSE(fs::exists(killed / "meta.json"));
  const ProgramRun resumed = run_command_line(sweep + " --resume --out " + killed.string());
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  const auto meta = nlohmann::json::parse(slurp(killed / "meta.json"));
  EXPECT_GE(meta["run"]["points_reused_from_checkpoint"].get<int>(), 5);
  EXPECT_EQ(slurp(whole / "bifurcation.csv"), slurp(killed / "bifurcation.csv"));
  EXPECT_EQ(slurp(whole / "summary.csv"), slurp(killed / "summary.csv"));
}

TEST(Sweep, PlotWritesAPngOrSaysWhyNot) {
  const ScratchFolder scratch;
  const auto out = scratch / "plot";
  const ProgramRun o = run_command_line(
      "sweep linear_impact --param omega=2:2.5:6 --transient 20 --points 8 "
      "--quiet --plot --out " +
      out.string());
  ASSERT_EQ(o.status, 0) << o.err;
  EXPECT_TRUE(fs::exists(out / "bifurcation.csv"));
  if (run_program({"/usr/bin/python3", "-c", "import matplotlib"}, ProgramOutput::discard) == 0)
    EXPECT_TRUE(fs::exists(out / "bifurcation.png")) << o.err;
  else
    EXPECT_NE(o.err.find("plot skipped"), std::string::npos) << o.err;
}

// The plots run under $IMPACTLAB_PYTHON where it is set: a stand-in
// interpreter records how it was called.
TEST(Plots, RunUnderThePythonImpactlabPythonNames) {
  const ScratchFolder scratch;
  const auto python = scratch / "python";
  std::ofstream(python) << "#!/bin/sh\necho \"$@\" > \"$0.called\"\n";
  fs::permissions(python, fs::perms::owner_all);
  const auto out = scratch / "section";
  const ProgramRun run = run_command_line(
      "poincare jin2003 --transient 5 --points 5 --plot --quiet --out " + out.string(),
      {.environment = {"IMPACTLAB_PYTHON=" + python.string()}});
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string called = slurp(scratch / "python.called");
  EXPECT_NE(called.find("plot_sweep.py poincare " + (out / "poincare.csv").string()),
            std::string::npos)
      << called;
}

// simulate --plot draws simulation.png as the other commands draw theirs,
// sampling the run itself where --sample is not given.
TEST(Plots, SimulateDrawsItsPicture) {
  const ScratchFolder scratch;
  const auto out = scratch / "run";
  const ProgramRun run =
      run_command_line("simulate jin2003 --periods 20 --plot --quiet --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  // 64 samples per forcing period, and the end
  EXPECT_EQ(count_lines(slurp(out / "trajectory.csv")), 1 + 20 * 64 + 1);
  if (run_program({"/usr/bin/python3", "-c", "import matplotlib"}, ProgramOutput::discard) == 0)
    EXPECT_TRUE(fs::exists(out / "simulation.png")) << run.err;
  else
    EXPECT_NE(run.err.find("simulation.png not drawn"), std::string::npos) << run.err;
}

TEST(Periodic, DetectsThePeriodAndReportsFloquetMultipliers) {
  const ScratchFolder scratch;
  // jin2003: the stroboscopic points repeat every second period
  const auto out = scratch / "periodic";
  ASSERT_EQ(run_command_line("periodic jin2003 --quiet --out " + out.string()).status, 0);
  auto result = nlohmann::json::parse(slurp(out / "periodic.json"));
  EXPECT_EQ(result["request"]["period"], 2);
  EXPECT_TRUE(result["converged"]);
  EXPECT_LT(result["floquet_multipliers"][0]["abs"].get<double>(), 1.0);
  // every component of the state named, the coordinates as the scene's keys
  EXPECT_EQ(result["state_names"],
            nlohmann::json({"theta", "theta_dot", "friction_work"}));
  EXPECT_EQ(result["state_names"].size(), result["state"].size());

  // the linear impact oscillator's one-impact orbit: det M = r² e^{−2ζT}
  // (the flow contracts areas by e^{−2ζT}, the impact by r²)
  ASSERT_EQ(run_command_line("periodic linear_impact --quiet --out " + out.string()).status, 0);
  result = nlohmann::json::parse(slurp(out / "periodic.json"));
  EXPECT_EQ(result["request"]["period"], 1);
  EXPECT_EQ(result["state_names"], nlohmann::json({"x", "x_dot"}));
  const double product = result["floquet_multipliers"][0]["abs"].get<double>() *
                         result["floquet_multipliers"][1]["abs"].get<double>();
  EXPECT_NEAR(product, 0.8 * 0.8 * std::exp(-2.0 * 0.05 * std::numbers::pi), 1e-10);
}

// At ω = 6.3 rad/s the attractor is chaotic: no period shows in 64
// stroboscopic points, period 1 is tried from the transient's end, and one
// Newton iteration allowed leaves the search unconverged (a residual of
// 1.4e-4 when this was written, against the default tolerance of 1e-11).
// The summary says why, prints no multipliers of the iterate that is not an
// orbit (nor does periodic.json hold any), and says how the period was chosen.
TEST(Periodic, AnUnconvergedSearchSaysWhyAndPrintsNoMultipliers) {
  const ScratchFolder scratch;
  const auto out = scratch / "stalled";
  const ProgramRun run = run_command_line(
      "periodic jin2003 --set omega=6.3 --max-iterations 1 --out " + out.string());
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.out.find("NOT converged after"), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("multipliers"), std::string::npos) << run.out;
  const auto result = nlohmann::json::parse(slurp(out / "periodic.json"));
  ASSERT_FALSE(result["converged"].get<bool>());
  // nor does the file hold multipliers: the iterate's monodromy, 2 × 2, stays
  EXPECT_TRUE(result["floquet_multipliers"].empty()) << result["floquet_multipliers"];
  EXPECT_EQ(result["monodromy"].size(), 2u);
  const std::string failure = result["failure"];
  ASSERT_FALSE(failure.empty());
  EXPECT_NE(run.out.find(failure), std::string::npos) << run.out;
  EXPECT_NE(failure.find("max_iterations reached"), std::string::npos) << failure;
  EXPECT_NE(run.err.find("the period was not detected in 64 stroboscopic points"),
            std::string::npos)
      << run.err;
}

struct BadCase {
  std::string arguments;
  std::string key, value;
};

class SweepBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SweepBadInput, ExitsTwoWithOneLineNamingKeyAndValue) {
  const ScratchFolder scratch;
  const auto out = scratch / "bad";
  const ProgramRun o = run_command_line(GetParam().arguments + " --out " + out.string());
  EXPECT_TRUE(refused_naming(o, GetParam().key));
  EXPECT_NE(o.err.find(GetParam().value), std::string::npos) << o.err;
  EXPECT_FALSE(fs::exists(out / "bifurcation.csv"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SweepBadInput,
    ::testing::Values(BadCase{"sweep jin2003 --param omega=5:9", "--param", "omega=5:9"},
                      BadCase{"sweep jin2003 --param omega=5:x:4", "--param", "omega=5:x:4"},
                      BadCase{"sweep jin2003 --param e_n=0:2:5", "e_n", "2"},
                      BadCase{"sweep jin2003 --param colour=0:1:5", "--param", "colour"},
                      BadCase{"sweep jin2003 --param model=0:1:5", "--param", "model"},
                      BadCase{"sweep jin2003 --param omega=5:9:4 --direction sideways",
                              "--direction", "sideways"},
                      BadCase{"sweep jin2003 --param omega=5:9:4 --section moon", "--section",
                              "moon"},
                      BadCase{"sweep jin2003 --param omega=5:9:4 --batch maybe", "--batch",
                              "maybe"},
                      BadCase{"sweep jin2003 --param omega=5:9:4 --param V0=1:2:2 "
                              "--classification-tol sometimes",
                              "--classification-tol", "sometimes"},
                      BadCase{"sweep jin2003 --param omega=5:9:4 --param V0=1:2:2 "
                              "--set integrator.classification_method=euler",
                              "integrator.classification_method", "euler"},
                      BadCase{"poincare jin2003 --section impact:2", "--section", "impact:2"},
                      BadCase{"poincare jin2003 --section strobe:nan", "--section",
                              "strobe:nan"},
                      BadCase{"poincare jin2003 --section q=0.01:sideways", "--section",
                              "q=0.01:sideways"},
                      BadCase{"periodic jin2003 --period 0", "--period", "0"},
                      BadCase{"sweep jin2003 --set model=rigid --set spin=free --set radius=0 "
                              "--param mu=0:1:3",
                              "spin", "free"},
                      // at rest on the wall where μ makes the contact problem unsolvable
                      BadCase{"sweep jin2003 --set model=rigid --set mu=20 "
                              "--set initial.theta=0.07148944988552054 "
                              "--set initial.theta_dot=0 --param V0=1:2:3",
                              "mu", "20"},
                      BadCase{"periodic jin2003 --set model=rigid --set mu=20 "
                              "--set initial.theta=-0.07148944988552054 "
                              "--set initial.theta_dot=0",
                              "mu", "20"}));

}  // namespace
