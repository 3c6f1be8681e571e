// `impactlab continue --all`: every orbit that periodic --all finds at the
// start of the range is continued, so that a branch the scene's own
// attractor is not on appears: on the linear impact oscillator with its stop
// at σ = 0.5, just below the fold of its one-impact period-1 branch, the
// plain continuation follows the non-impacting orbit the scene settles on
// and sees no fold; with --all the fold's branch appears too, continued once
// although both orbits of its pair are found. On the bouncing ball the
// period-2 orbits of one impact per two table periods form a branch that no
// path joins to the period-1 branch the ball settles on: --all shows it,
// with its fold and multipliers at their closed forms.
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab::testing;

const std::string scene_and_range =
    "continue linear_impact --set sigma=0.5 --set initial.x=0.2 --param omega=1.86:1.95 "
    "--quiet";

int folds(const std::vector<std::vector<std::string>>& points) {
  int count = 0;
  for (std::size_t r = 1; r < points.size(); ++r) count += points[r][0] == "fold" ? 1 : 0;
  return count;
}

TEST(ContinueAll, ContinuesEveryOrbitFoundAndEachBranchOnce) {
  const ScratchFolder scratch;
  const auto plain = scratch / "plain";
  ASSERT_EQ(run_command_line(scene_and_range + " --out " + plain.string()).status, 0);
  const auto plain_record = nlohmann::json::parse(slurp(plain / "continuation.json"));
  ASSERT_EQ(plain_record["branches"].size(), 1U);
  EXPECT_EQ(folds(read_csv(plain / "points.csv")), 0);

  const auto every = scratch / "every";
  const ProgramRun run = run_command_line(scene_and_range +
                                          " --all --starts 100 --box initial.x=-4:0.5 "
                                          "--box initial.x_dot=-4:4 --out " + every.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto record = nlohmann::json::parse(slurp(every / "continuation.json"));
  const auto& orbits = record["all"]["orbits"];
  const auto& branches = record["branches"];
  ASSERT_GE(orbits.size(), 3U);  // the non-impacting orbit and the fold's pair
  // each orbit either has a branch of its own or is on an earlier one
  std::set<int> continued;
  for (const auto& branch : branches) continued.insert(branch["orbit"].get<int>());
  EXPECT_EQ(continued.size(), branches.size());
  EXPECT_EQ(continued.size() + record["all"]["not_continued"].size(), orbits.size());
  EXPECT_NE(record["all"]["not_continued"].dump().find("on the branch of orbit"),
            std::string::npos);
  // the fold, once: both orbits of its pair lie on one branch
  EXPECT_EQ(folds(read_csv(every / "points.csv")), 1);
}

// The ball on a table z = A sin ωt (g = 9.81 m/s², ω = 30 rad/s, r = 0.8)
// has period-n orbits of one impact per n table periods where the impact
// phase φ satisfies cos φ = nπ(1 − r) g / ((1 + r) A ω²): a pair of them
// for A above the fold A_n = nπ(1 − r) g / ((1 + r) ω²), where cos φ = 1
// and the multipliers are 1 and det M = r² (one impact).
TEST(ContinueAll, ShowsTheBallsPeriodTwoBranchDisconnectedFromItsAttractor) {
  // the start settles on the period-1 orbit of one impact per table period
  const std::string ball =
      "continue bouncing_ball --set initial.y=0 --set initial.y_dot=1 --param A=0.0112:0.006 "
      "--quiet";
  const double gravity = 9.81, omega = 30.0, restitution = 0.8;
  const double fold_period_two =
      2.0 * std::numbers::pi * (1.0 - restitution) * gravity / ((1.0 + restitution) * omega * omega);
  const double fold_period_one = fold_period_two / 2.0;
  ASSERT_LT(fold_period_one, 0.006);  // the attractor's own fold lies below the range

  const ScratchFolder scratch;
  const auto plain = scratch / "plain";
  ASSERT_EQ(run_command_line(ball + " --out " + plain.string()).status, 0);
  const auto plain_record = nlohmann::json::parse(slurp(plain / "continuation.json"));
  ASSERT_EQ(plain_record["branches"].size(), 1U);
  EXPECT_EQ(plain_record["branches"][0]["period"].get<int>(), 1);
  EXPECT_EQ(folds(read_csv(plain / "points.csv")), 0);

  const auto every = scratch / "every";
  const ProgramRun run = run_command_line(
      ball + " --all --period 2 --starts 200 --box initial.y=0:0.3 --box initial.y_dot=-2:2 --out " +
      every.string());
  ASSERT_EQ(run.status, 0) << run.err;
  // the attractor's own branch is among them: its start is the plain run's
  const auto plain_branch = read_csv(plain / "branch.csv");
  const auto every_branch = read_csv(every / "branch.csv");
  ASSERT_EQ(every_branch[0][0] + "," + every_branch[0][1] + "," + every_branch[0][2], "A,q,qdot");
  bool attractor_found = false;
  for (std::size_t r = 1; r < every_branch.size(); ++r)
    attractor_found = attractor_found ||
                      (std::abs(std::stod(every_branch[r][1]) - std::stod(plain_branch[1][1])) < 1e-8 &&
                       std::abs(std::stod(every_branch[r][2]) - std::stod(plain_branch[1][2])) < 1e-8 &&
                       std::abs(std::stod(every_branch[r][0]) - std::stod(plain_branch[1][0])) < 1e-12);
  EXPECT_TRUE(attractor_found);
  const auto points = read_csv(every / "points.csv");
  const auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < points[0].size(); ++c)
      if (points[0][c] == name) return c;
    ADD_FAILURE() << "points.csv has no column " << name;
    return std::size_t{0};
  };
  int period_two_folds = 0;
  for (std::size_t r = 1; r < points.size(); ++r) {
    if (points[r][0] != "fold" || points[r][column("period")] != "2") continue;
    const double amplitude = std::stod(points[r][column("A")]);
    if (std::abs(amplitude - fold_period_two) > 1e-6) continue;  // another period-2 orbit's fold
    ++period_two_folds;
    EXPECT_NEAR(amplitude, fold_period_two, 1e-9 * fold_period_two);
    EXPECT_NEAR(std::stod(points[r][column("multiplier1_re")]), 1.0, 1e-9);
    EXPECT_NEAR(std::stod(points[r][column("multiplier2_re")]), restitution * restitution, 1e-9);
  }
  EXPECT_EQ(period_two_folds, 1);
}

TEST(ContinueAll, RefusesWhatItCannotDo) {
  EXPECT_TRUE(refused_naming(
      run_command_line(scene_and_range + " --all --param2 sigma=0.5:0.6 --out /dev/null/x"),
      "--param2"));
  EXPECT_TRUE(refused_naming(
      run_command_line(scene_and_range + " --all --section impact:1 --out /dev/null/x"),
      "--section"));
  EXPECT_TRUE(refused_naming(
      run_command_line(scene_and_range + " --all --starts 0 --out /dev/null/x"), "--starts"));
  EXPECT_TRUE(refused_naming(
      run_command_line(scene_and_range + " --all --box initial.x=1:2 --out /dev/null/x"),
      "--box"));
}

}  // namespace
}  // namespace impactlab
