// Basins of attraction (analysis/basins.hpp, `impactlab basins`): attractors
// told apart by their canonical section point and numbered by first
// appearance; the bouncing ball with Γ = Aω²/g = 0.9 < 1, where the table
// never pulls away from a ball at rest, so two attractors coexist and both are
// known in closed form, written here:
// * resting on the table, y = A sin ωt: on the section ωt ≡ 0, (0, Aω), no impact;
// * the period-1 orbit, one impact per period, taking off at the phase φ with
//   cos φ = π(1 − r)/(Γ(1 + r)) at speed gT/2 (stable for Γ below the period
//   doubling at Γ² = (π(1 − r)/(1 + r))² + (2(1 + r²)/(1 + r)²)²).
// Serial, threaded, MPI and resumed runs write identical files.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <impactlab/analysis/basins.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using impactlab::SweepRecord;
using namespace impactlab::testing;

SweepRecord record_with_cycle(const std::vector<std::array<double, 2>>& points, int period,
                              double impacts_per_period) {
  SweepRecord record;
  record.result.termination = impactlab::SectionTermination::completed;
  for (const auto& p : points) record.result.points.push_back({0.0, p[0], p[1], 0});
  record.classification.period = period;
  record.classification.impacts_per_period = impacts_per_period;
  return record;
}

TEST(Basins, OneCycleSeenFromEitherPointIsOneAttractorNumberedByFirstAppearance) {
  // a period-2 cycle {a, b} recorded from a and from b, a period-1 orbit at c,
  // and a point with no period found
  const std::array<double, 2> a{0.5, 1.0}, b{-0.25, 2.0}, c{0.1, 0.1};
  const auto from_a = record_with_cycle({a, b, a, b, a, b}, 2, 1.0);
  const auto from_b = record_with_cycle({b, a, b, a, b, a}, 2, 1.0);
  const auto fixed = record_with_cycle({c, c, c, c}, 1, 1.0);
  auto none = record_with_cycle({a, c, b, c}, 0, 1.0);
  // the same point but more impacts per period: another attractor
  const auto other = record_with_cycle({c, c, c, c}, 1, 2.0);
  const auto map =
      impactlab::identify_attractors({&fixed, &from_a, &none, &from_b, &other, &fixed}, 1e-6);
  EXPECT_EQ(map.attractor, (std::vector<int>{1, 2, 0, 2, 3, 1}));
  ASSERT_EQ(map.attractors.size(), 3u);
  EXPECT_EQ(map.attractors[1].point, b);  // the lexicographically smallest of the cycle
  EXPECT_EQ(map.attractors[1].basin_points, 2);
  EXPECT_EQ(map.unclassified, 1);
}

constexpr double g = 9.81, omega = 30.0, r = 0.8, A = 0.00981;  // Γ = 0.9
const std::string basins = "basins bouncing_ball --set A=0.00981 --x initial.y=0:0.1:12 "
                           "--y initial.y_dot=-1:1:8 --quiet";

TEST(Basins, BouncingBallRestAndPeriodOneOrbitCoexistAsTheClosedFormsSay) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun o = run_command_line(basins + " --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.err;
  const auto basin_lines = split_lines(slurp(out / "basins.csv"));
  EXPECT_EQ(basin_lines[0], "initial.y,initial.y_dot,attractor,period,impacts_per_period,contact,"
                            "termination,transient_end");
  EXPECT_EQ(basin_lines.size(), 1u + 96u);

  // the closed forms
  const double period = 2.0 * std::numbers::pi / omega, gamma = A * omega * omega / g;
  const double phase = std::acos(std::numbers::pi * (1.0 - r) / (gamma * (1.0 + r)));
  const double flight = period - phase / omega, speed = g * period / 2.0;
  const double bouncing_y = A * std::sin(phase) + speed * flight - 0.5 * g * flight * flight;
  const double bouncing_v = speed - g * flight;

  bool resting = false, bouncing = false;
  int attractors = 0;
  std::stringstream table(slurp(out / "attractors.csv"));
  std::string line;
  std::getline(table, line);
  EXPECT_EQ(line, "attractor,period,impacts_per_period,contact,q,qdot,basin_points");
  while (std::getline(table, line)) {
    int id = 0, p = 0, contact = 0, count = 0;
    double impacts = 0.0, q = 0.0, qdot = 0.0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%d,%lf,%d,%lf,%lf,%d", &id, &p, &impacts, &contact, &q,
                          &qdot, &count),
              7)
        << line;
    ++attractors;
    EXPECT_EQ(id, attractors);
    EXPECT_GT(count, 3) << line;
    if (p == 1 && impacts == 0.0) {
      resting = true;
      EXPECT_NEAR(q, 0.0, 1e-12);
      EXPECT_NEAR(qdot, A * omega, 1e-12);
    }
    if (p == 1 && impacts == 1.0) {
      bouncing = true;
      EXPECT_NEAR(q, bouncing_y, 1e-9);
      EXPECT_NEAR(qdot, bouncing_v, 1e-9);
    }
  }
  EXPECT_TRUE(resting);
  EXPECT_TRUE(bouncing);
  EXPECT_EQ(attractors, 2);
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  EXPECT_EQ(meta["sweep"]["basins"], true);
}

TEST(Basins, SerialThreadedMpiAndResumedRunsWriteIdenticalFiles) {
  const ScratchFolder scratch;
  ASSERT_EQ(run_command_line(basins + " --threads 1 --out " + (scratch / "serial").string()).status,
            0);
  ASSERT_EQ(
      run_command_line(basins + " --threads 2 --out " + (scratch / "threaded").string()).status, 0);
  for (const char* file : {"basins.csv", "attractors.csv"})
    EXPECT_EQ(slurp(scratch / "serial" / file), slurp(scratch / "threaded" / file)) << file;
  // stopped after 30 points, then resumed
  EXPECT_EQ(
      run_command_line(basins + " --stop-after 30 --out " + (scratch / "resumed").string()).status,
      3);
  EXPECT_FALSE(fs::exists(scratch / "resumed" / "basins.csv"));
  ASSERT_EQ(run_command_line(basins + " --resume --out " + (scratch / "resumed").string()).status,
            0);
  for (const char* file : {"basins.csv", "attractors.csv"})
    EXPECT_EQ(slurp(scratch / "serial" / file), slurp(scratch / "resumed" / file)) << file;
  if (!mpirun_found()) GTEST_SKIP() << "no mpirun";
  const ProgramRun mpi =
      run_command_line(basins + " --out " + (scratch / "mpi").string(), {.mpi_ranks = 2});
  if (mpi.err.find("built without MPI") != std::string::npos) GTEST_SKIP() << "built without MPI";
  ASSERT_EQ(mpi.status, 0) << mpi.err;
  for (const char* file : {"basins.csv", "attractors.csv"})
    EXPECT_EQ(slurp(scratch / "serial" / file), slurp(scratch / "mpi" / file)) << file;
}

TEST(Basins, BadInputExitsWithTwoAndOneLine) {
  // each command line and the key or option its message must name
  const std::vector<std::pair<std::string, std::string>> bad = {
      // the same key twice
      {"basins bouncing_ball --x initial.y=0:0.1:4 --y initial.y=0:1:4", "--y"},
      // malformed
      {"basins bouncing_ball --x initial.y=0:0.1 --y initial.y_dot=0:1:4", "--x"},
      // no such key
      {"basins bouncing_ball --x colour=0:1:4 --y initial.y_dot=0:1:4", "--x"},
      // r outside [0, 1]
      {"basins bouncing_ball --x initial.y=0:0.1:4 --y r=0:2:4", "r"},
      // --y missing
      {"basins bouncing_ball --x initial.y=0:0.1:4", "--y"},
      {"basins bouncing_ball --x initial.y=0:0.1:4 --y initial.y_dot=0:1:4 --attractor-tol 0",
       "--attractor-tol"},
  };
  for (const auto& [arguments, key] : bad) {
    const ScratchFolder scratch;
    const ProgramRun o = run_command_line(arguments + " --out " + (scratch / "out").string());
    EXPECT_TRUE(refused_naming(o, key)) << arguments;
    if (arguments.find("colour") != std::string::npos) {
      EXPECT_NE(o.err.find("--x = colour"), std::string::npos) << o.err;
    }
    EXPECT_FALSE(fs::exists(scratch / "out" / "basins.csv")) << arguments;
  }
}

}  // namespace
