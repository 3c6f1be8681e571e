// `impactlab periodic --all` end to end: orbits.csv (one row per orbit, the
// state by its components' names) and periodic.json (the `orbits` list, the
// units, the starts' outcomes, the box) agree with each other; the same seed
// writes the same files; bad input exits 2 with one line naming the option
// and writes nothing.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab::testing;

TEST(PeriodicAll, OrbitsCsvAndPeriodicJsonDescribeTheSameOrbits) {
  const ScratchFolder scratch;
  const auto out = scratch / "orbits";
  const ProgramRun run = run_command_line("periodic linear_impact --all --period 1 --starts 40 "
                                          "--box initial.x=-2:0.2 --box initial.x_dot=-3:3 "
                                          "--quiet --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto rows = read_csv(out / "orbits.csv");
  ASSERT_GE(rows.size(), 2U);
  const std::vector<std::string> header = {"id", "minimal_period", "x", "x_dot", "impacts",
                                           "contact_phases", "stable", "multiplier1_re",
                                           "multiplier1_im", "multiplier2_re", "multiplier2_im",
                                           "residual"};
  EXPECT_EQ(rows[0], header);
  const auto record = nlohmann::json::parse(slurp(out / "periodic.json"));
  const auto& orbits = record["orbits"];
  ASSERT_EQ(orbits.size(), rows.size() - 1);
  for (std::size_t k = 0; k < orbits.size(); ++k) {
    const auto& row = rows[k + 1];
    EXPECT_EQ(std::stoi(row[0]), orbits[k]["id"].get<int>());
    EXPECT_EQ(std::stoi(row[1]), orbits[k]["minimal_period"].get<int>());
    EXPECT_EQ(std::stod(row[2]), orbits[k]["state"][0].get<double>());
    EXPECT_EQ(std::stod(row[3]), orbits[k]["state"][1].get<double>());
    EXPECT_EQ(std::stoi(row[6]) == 1, orbits[k]["stable"].get<bool>());
    EXPECT_EQ(std::stod(row[7]), orbits[k]["floquet_multipliers"][0]["re"].get<double>());
  }
  EXPECT_EQ(record["units"]["x"], "length");  // the scene key initial.x's unit
  EXPECT_EQ(record["state_names"], nlohmann::json({"x", "x_dot"}));
  EXPECT_EQ(record["request"]["box"][0]["key"], "initial.x");
  EXPECT_EQ(record["request"]["starts"], 40);
  EXPECT_TRUE(record["request"]["deflation"]["enabled"].get<bool>());
  const auto& starts = record["starts"];
  EXPECT_EQ(starts["new_orbit"].get<int>() + starts["known_orbit"].get<int>() +
                starts["not_converged"].get<int>() + starts["stopped"].get<int>(),
            40);
  EXPECT_EQ(starts["new_orbit"].get<std::size_t>(), orbits.size());
  EXPECT_EQ(starts["outcomes"].size(), 40U);
  EXPECT_TRUE(record.contains("command"));
  EXPECT_TRUE(record.contains("scene"));

  // the same seed draws the same starts: the same file
  const auto again = scratch / "again";
  ASSERT_EQ(run_command_line("periodic linear_impact --all --period 1 --starts 40 "
                             "--box initial.x=-2:0.2 --box initial.x_dot=-3:3 --quiet --out " +
                             again.string())
                .status,
            0);
  EXPECT_EQ(slurp(out / "orbits.csv"), slurp(again / "orbits.csv"));
}

TEST(PeriodicAll, APlainRunInTheSameFolderLeavesNoStaleOrbits) {
  const ScratchFolder scratch;
  const auto out = scratch / "shared";
  ASSERT_EQ(run_command_line("periodic linear_impact --all --quiet --out " + out.string()).status,
            0);
  ASSERT_TRUE(std::filesystem::exists(out / "orbits.csv"));
  ASSERT_EQ(run_command_line("periodic linear_impact --quiet --out " + out.string()).status, 0);
  EXPECT_FALSE(std::filesystem::exists(out / "orbits.csv"));
  EXPECT_TRUE(std::filesystem::exists(out / "periodic.json"));
}

TEST(PeriodicAll, TheBallsRecordGivesItsStateUnits) {
  const ScratchFolder scratch;
  const auto out = scratch / "ball";
  ASSERT_EQ(run_command_line("periodic bouncing_ball --all --quiet --out " + out.string()).status,
            0);
  const auto record = nlohmann::json::parse(slurp(out / "periodic.json"));
  EXPECT_EQ(record["units"]["y"], "m");
  EXPECT_EQ(record["units"]["y_dot"], "m/s");
  EXPECT_EQ(record["units"]["t_section"], "s");
  // the default box: both initial-state keys, the height kept above the table
  ASSERT_EQ(record["request"]["box"].size(), 2U);
  EXPECT_GE(record["request"]["box"][0]["from"].get<double>(), 0.0);
}

struct BadAll {
  std::string arguments;
  std::string option;  // the flag the one line names
};

class PeriodicAllBadInput : public ::testing::TestWithParam<BadAll> {};

TEST_P(PeriodicAllBadInput, ExitsTwoNamingTheOptionAndWritesNothing) {
  const ScratchFolder scratch;
  const auto out = scratch / "bad";
  const ProgramRun run = run_command_line("periodic linear_impact --all " + GetParam().arguments +
                                          " --out " + out.string());
  EXPECT_TRUE(refused_naming(run, GetParam().option)) << run.err;
  EXPECT_FALSE(std::filesystem::exists(out / "orbits.csv"));
  EXPECT_FALSE(std::filesystem::exists(out / "periodic.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PeriodicAllBadInput,
    ::testing::Values(BadAll{"--starts 0", "--starts"}, BadAll{"--starts -3", "--starts"},
                      BadAll{"--box initial.x=1", "--box"},
                      BadAll{"--box initial.x=0:2", "--box"},  // past the stop at 0.2
                      BadAll{"--box initial.nope=0:1", "--box"},
                      BadAll{"--box sigma=0:0.1", "--box"},
                      BadAll{"--box initial.x=-1:0 --box initial.x=-2:0", "--box"},
                      BadAll{"--period 0", "--period"},
                      // no start converges in one Newton iteration
                      BadAll{"--starts 3 --max-iterations 1", "--starts"}));

TEST(PeriodicAll, NoOrbitSaysSoInOneLine) {
  const ScratchFolder scratch;
  const ProgramRun run =
      run_command_line("periodic linear_impact --all --starts 3 --max-iterations 1 --out " +
                       (scratch / "none").string());
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("periodic --all: no orbit of period 1 from 3 starts"), std::string::npos)
      << run.err;
  EXPECT_EQ(count_lines(run.err), 1);
}

}  // namespace
}  // namespace impactlab
