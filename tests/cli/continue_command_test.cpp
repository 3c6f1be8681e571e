// `impactlab continue` from the command line: the files it writes, and bad
// input (exit status 2 and one line naming the key and value).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

TEST(ContinueCommand, WritesTheBranchThePointsAndTheSidecar) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome =
      run_command_line("continue linear_impact --param omega=2:2.5 --quiet --out " + out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::string branch = slurp(out / "branch.csv");
  EXPECT_EQ(branch.rfind("omega,q,qdot,period,branch,impacts,contact_phases,stable,", 0), 0u);
  EXPECT_GT(count_lines(branch), 20);
  const std::string points = slurp(out / "points.csv");
  EXPECT_EQ(points.rfind("type,omega,q,qdot,", 0), 0u);
  EXPECT_NE(points.find("period_doubling,2.265"), std::string::npos) << points;
  EXPECT_NE(points.find("grazing,2.44"), std::string::npos) << points;
  const auto meta = nlohmann::json::parse(slurp(out / "continuation.json"));
  EXPECT_EQ(meta["branches"][0]["stop_reason"], "signature_change");
  EXPECT_EQ(meta["request"]["parameter"], "omega");
  // no temporary files left
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
}

TEST(ContinueCommand, ImpactSectionWritesThePhaseAndRateOfTheImpact) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.4 --section impact:+1 "
      "--quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::string points = slurp(out / "points.csv");
  EXPECT_NE(points.find("period_doubling,2.265297"), std::string::npos) << points;
  const auto meta = nlohmann::json::parse(slurp(out / "continuation.json"));
  EXPECT_EQ(meta["request"]["section"], "impact:1");
  EXPECT_EQ(meta["branches"][0]["stop_reason"], "end_of_range");
  EXPECT_NE(meta["columns"]["branch.csv"]["q, qdot"].get<std::string>().find("phase"),
            std::string::npos);
}

// On the impact section: the branch ends where its own impact grazes, the
// point in points.csv, and the grazing curve from it (--param2) in curve.csv.
TEST(ContinueCommand, ImpactSectionLocatesItsOwnGrazeAndFollowsItsCurve) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.5 --section impact:+1 "
      "--param2 sigma=0.2:0.3 --curve grazing --quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::string points = slurp(out / "points.csv");
  EXPECT_NE(points.find("grazing,2.448265181"), std::string::npos) << points;
  const auto meta = nlohmann::json::parse(slurp(out / "continuation.json"));
  EXPECT_EQ(meta["branches"][0]["stop_reason"], "signature_change");
  const std::string curve = slurp(out / "curve.csv");
  EXPECT_EQ(curve.rfind("omega,sigma,q,qdot,multiplier1_re,", 0), 0u) << curve;
  EXPECT_GT(count_lines(curve), 10);
  const auto curve_meta = nlohmann::json::parse(slurp(out / "curve.json"));
  EXPECT_EQ(curve_meta["type"], "grazing");
  EXPECT_EQ(curve_meta["stop_reason"], "end_of_range");
  EXPECT_EQ(curve_meta["request"]["section"], "impact:1");
  EXPECT_NE(curve_meta["columns"]["q, qdot"].get<std::string>().find("phase"), std::string::npos);
}

TEST(ContinueCommand, TwoParameterCurveWritesTheCurveAndItsSidecar) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.5 --param2 sigma=0.2:0.3 "
      "--curve grazing --quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::string curve = slurp(out / "curve.csv");
  EXPECT_EQ(curve.rfind("omega,sigma,q,qdot,multiplier1_re,", 0), 0u) << curve;
  EXPECT_GT(count_lines(curve), 10);
  EXPECT_NE(curve.find("2.448265181"), std::string::npos) << curve;  // the start: the located graze
  const auto meta = nlohmann::json::parse(slurp(out / "curve.json"));
  EXPECT_EQ(meta["type"], "grazing");
  EXPECT_EQ(meta["stop_reason"], "end_of_range");
  EXPECT_EQ(meta["request"]["parameter2"], "sigma");
  EXPECT_TRUE(meta["columns"].contains("graze_time"));
  EXPECT_TRUE(fs::exists(out / "branch.csv"));
}

// The plastic stop (r = 0): the branch's located contact end, then its curve
// in (omega, sigma) from its own defining condition (the push on the mass at
// rest at its landing is zero), in curve.csv and curve.json.
TEST(ContinueCommand, ContactEndCurveWritesTheCurveAndItsSidecar) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --set r=0 --param omega=1.5:1.8 --param2 sigma=0.2:0.3 "
      "--curve contact_end --quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(slurp(out / "points.csv").find("contact_end,1.670310638"), std::string::npos)
      << slurp(out / "points.csv");
  const std::string curve = slurp(out / "curve.csv");
  EXPECT_EQ(curve.rfind("omega,sigma,q,qdot,multiplier1_re,", 0), 0u) << curve;
  EXPECT_GT(count_lines(curve), 5);
  const auto meta = nlohmann::json::parse(slurp(out / "curve.json"));
  EXPECT_EQ(meta["type"], "contact_end");
  EXPECT_EQ(meta["stop_reason"], "end_of_range");
  EXPECT_EQ(meta["request"]["curve"], "contact_end");
}

TEST(ContinueCommand, SwitchWithACurveWritesTheDoubledBranchsCurveToo) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue bouncing_ball --param A=0.0112:0.025 --start "
      "0.044286522498880876,-0.6269934342801218 --param2 r=0.8:0.75 "
      "--curve period_doubling --switch --quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::string curve = slurp(out / "curve.csv");
  EXPECT_NE(curve.find("newton_iterations,branch,period,type,start\n"), std::string::npos)
      << curve;
  // rows of branch 1, period 2, started on that branch
  EXPECT_NE(curve.find(",1,2,period_doubling,branch\n"), std::string::npos) << curve;
  const auto meta = nlohmann::json::parse(slurp(out / "curve.json"));
  EXPECT_EQ(meta["request"]["switch"], true);
  ASSERT_GE(meta["doubled_curves"].size(), 1u);
  EXPECT_EQ(meta["doubled_curves"][0]["period"], 2);
  EXPECT_EQ(meta["doubled_curves"][0]["type"], "period_doubling");
  EXPECT_EQ(meta["doubled_curves"][0]["stop_reason"], "end_of_range");
}

TEST(ContinueCommand, BadInputExitsWithTwoAndOneLineNamingTheKey) {
  // each command line and the key its message must name ("impactlab: KEY = ...")
  const std::vector<std::pair<std::string, std::string>> bad = {
      // outside the key's range; no such key; a malformed range; no such period
      {"continue linear_impact --param omega=-1:2", "omega"},
      {"continue linear_impact --param zeta2=0:1", "--param"},
      {"continue linear_impact --param omega=2", "--param"},
      {"continue linear_impact --param omega=2:2.5 --period 0", "--period"},
      // no Jacobians (Model P); a spinning ball without a radius
      {"continue jin2003 --set model=paper --param omega=6:7", "oscillator"},
      {"continue jin2003 --set model=rigid --set spin=free --param omega=6:7", "spin"},
      // no one wall; a wall never hit; neither strobe nor impact
      {"continue linear_impact --param omega=2:2.5 --section impact:0", "--section"},
      {"continue linear_impact --param omega=2:2.5 --section impact:-1", "--param"},
      {"continue linear_impact --param omega=2:2.5 --section q=0.1", "--section"},
      // no orbit from this start
      {"continue linear_impact --param omega=2:2.5 --period 3 --transient 0 --start 5,5",
       "--param"},
      // the same key twice; a malformed range; outside r's range; no such key
      {"continue linear_impact --param omega=2:2.5 --param2 omega=3:4", "--param2"},
      {"continue linear_impact --param omega=2:2.5 --param2 sigma=0.2", "--param2"},
      {"continue linear_impact --param omega=2:2.5 --param2 r=0.8:1.5", "r"},
      {"continue linear_impact --param omega=2:2.5 --param2 zeta2=0:1", "--param2"},
      // --curve without --param2; an unknown curve; one start number
      {"continue linear_impact --param omega=2:2.5 --curve fold", "--curve"},
      {"continue linear_impact --param omega=2:2.5 --param2 r=0.8:0.6 --curve torus", "--curve"},
      // a curve type the branch has no located point of (no contact phase at r = 0.8)
      {"continue linear_impact --param omega=2:2.5 --param2 sigma=0.2:0.3 --curve contact_end",
       "--curve"},
      {"continue linear_impact --param omega=2:2.5 --start 0.1", "--start"},
  };
  for (const auto& [arguments, key] : bad) {
    const ScratchFolder scratch;
    const ProgramRun outcome = run_command_line(arguments + " --out " + (scratch / "out").string());
    // "KEY = VALUE: reason" from the scene API, "FLAG: reason" from the parser
    EXPECT_TRUE(refused_naming(outcome, key)) << arguments;
    EXPECT_FALSE(fs::exists(scratch / "out" / "branch.csv")) << arguments;
  }
}

// The library names the option by its own name; the command line spells it
// and every option the message mentions as a flag, as it always has.
TEST(ContinueCommand, SameKeyTwiceNamesBothFlags) {
  const ScratchFolder scratch;
  const auto dir = scratch / "same_key";
  const ProgramRun outcome =
      run_command_line("continue linear_impact --param omega=2:2.5 --param2 omega=0.1:0.2 --out " +
              (dir / "out").string());
  EXPECT_EQ(outcome.status, 2);
  EXPECT_EQ(outcome.err, "impactlab: --param2 = omega: must differ from --param's key\n");
}

}  // namespace
