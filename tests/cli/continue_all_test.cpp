// `impactlab continue --all`: every orbit that periodic --all finds at the
// start of the range is continued, so that a branch the scene's own
// attractor is not on appears: on the linear impact oscillator with its stop
// at σ = 0.5, just below the fold of its one-impact period-1 branch, the
// plain continuation follows the non-impacting orbit the scene settles on
// and sees no fold; with --all the fold's branch appears too, continued once
// although both orbits of its pair are found.
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace {

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
