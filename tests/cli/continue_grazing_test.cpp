// `impactlab continue` at a located grazing point: the normal form's columns
// of points.csv, grazing.json (an entry per grazing point, with its units and
// provenance), --no-normal-forms, and --plot's grazing.png beside a sweep.
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

// a CSV file's columns by header name
std::map<std::string, std::vector<std::string>> columns_of(const fs::path& path) {
  const auto rows = read_csv(path);
  std::map<std::string, std::vector<std::string>> columns;
  if (rows.empty()) return columns;
  for (std::size_t i = 1; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[0].size(); ++j)
      columns[rows[0][j]].push_back(j < rows[i].size() ? rows[i][j] : "");
  return columns;
}

TEST(ContinueGrazing, WritesTheNormalFormsColumnsAndGrazingJson) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.5 --section impact:+1 --out " + out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_NE(outcome.out.find("normal form: jump for omega < 2.448265"), std::string::npos)
      << outcome.out;
  const auto rows = columns_of(out / "points.csv");
  ASSERT_EQ(rows.at("type").size(), 2u);
  EXPECT_EQ(rows.at("type")[1], "grazing");
  EXPECT_EQ(rows.at("scenario")[0], "");  // the period doubling's row
  EXPECT_EQ(rows.at("scenario")[1], "jump");
  EXPECT_EQ(rows.at("impacting_side")[1], "-1");
  EXPECT_NEAR(std::stod(rows.at("impact_speed_coefficient")[1]), 0.68520313929, 1e-9);
  EXPECT_NEAR(std::stod(rows.at("period_one_speed_slope")[1]), 0.73359486517, 1e-9);

  const auto grazing = nlohmann::json::parse(slurp(out / "grazing.json"));
  EXPECT_EQ(grazing["parameter"], "omega");
  EXPECT_TRUE(grazing.contains("scene") && grazing.contains("units") && grazing.contains("fields"));
  ASSERT_EQ(grazing["points"].size(), 1u);
  const auto& point = grazing["points"][0];
  EXPECT_EQ(point["row"], 1);
  EXPECT_EQ(point["scenario"], "jump");
  EXPECT_EQ(point["rule"], "not_applicable");
  EXPECT_NEAR(point["omega"].get<double>(), 2.448265181813, 1e-9);
  EXPECT_NEAR(point["discontinuity_map"]["jump"][1].get<double>(), 1.8, 1e-9);  // 1 + r
  EXPECT_EQ(point["attractors"].size(), 25u);
  EXPECT_EQ(point["normal_form"]["linear"].size(), 2u);
  // the continuation.json names the columns
  const auto meta = nlohmann::json::parse(slurp(out / "continuation.json"));
  EXPECT_TRUE(meta["columns"]["points.csv"].contains("scenario"));
}

TEST(ContinueGrazing, NoNormalFormsLeavesTheColumnsUnavailable) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.5 --section impact:+1 --no-normal-forms --quiet "
      "--out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const auto rows = columns_of(out / "points.csv");
  EXPECT_EQ(rows.at("scenario")[1], "unavailable");
  const auto grazing = nlohmann::json::parse(slurp(out / "grazing.json"));
  EXPECT_EQ(grazing["points"][0]["available"], false);
}

// A branch with no grazing point writes no grazing.json.
TEST(ContinueGrazing, NoGrazingNoFile) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.4 --section impact:+1 --quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_FALSE(fs::exists(out / "grazing.json"));
}

// --plot with --with-sweep: grazing.png, the prediction beside an impact
// section sweep through the graze (where matplotlib is there to draw it).
TEST(ContinueGrazing, PlotDrawsThePredictionBesideTheSweep) {
  const ScratchFolder scratch;
  const auto sweep = scratch / "sweep";
  const ProgramRun swept = run_command_line(
      "sweep linear_impact --param omega=2.44:2.4482:5 --section impact:1 --points 10 --quiet "
      "--out " +
      sweep.string());
  ASSERT_EQ(swept.status, 0) << swept.err;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue linear_impact --param omega=2:2.5 --section impact:+1 --quiet --with-sweep " +
      (sweep / "bifurcation.csv").string() + " --out " + out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  if (outcome.err.find("plot skipped") == std::string::npos) {
    EXPECT_TRUE(fs::exists(out / "continuation.png")) << outcome.err;
    EXPECT_TRUE(fs::exists(out / "grazing.png")) << outcome.err;
  }
}

// jin2003's own graze (ω = 8.5: the period-2 swing born from the hanging
// pendulum grazes both walls at V0 = 0.652035): continue predicts a jump,
// and a brute-force sweep through the graze on the impact section sees it,
// its impact speed the same 0.151 rad/s at every value past the graze (a
// distant impacting orbit, not one growing from zero as c√|μ|).
TEST(ContinueGrazing, Jin2003ScenarioAgreesWithASweepThroughItsGraze) {
  const ScratchFolder scratch;
  const auto out = scratch / "out";
  const ProgramRun outcome = run_command_line(
      "continue jin2003 --set omega=8.5 --param V0=0.05:1.5 --start 0,0 --switch --quiet --out " +
      out.string());
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const auto grazing = nlohmann::json::parse(slurp(out / "grazing.json"));
  ASSERT_EQ(grazing["points"].size(), 1u);
  const auto& point = grazing["points"][0];
  EXPECT_EQ(point["scenario"], "jump");
  EXPECT_EQ(point["further_touches"].size(), 1u);
  const double graze = point["V0"].get<double>(), c = point["impact_speed_coefficient"];
  const auto sweep = scratch / "sweep";
  const ProgramRun swept = run_command_line(
      "sweep jin2003 --set omega=8.5 --param V0=" + std::to_string(graze + 1e-5) + ":" +
      std::to_string(graze + 1e-3) + ":5 --section impact:1 --points 4 --quiet --out " +
      sweep.string());
  ASSERT_EQ(swept.status, 0) << swept.err;
  const auto rows = columns_of(sweep / "bifurcation.csv");
  ASSERT_FALSE(rows.at("qdot").empty());
  // the gap θ₀ − θ (rad): its rate is |q̇| times |∂h/∂θ| = 1
  const double gap_per_rate = std::fabs(point["discontinuity_map"]["gap_gradient"][0].get<double>());
  double slowest = INFINITY, fastest = 0.0;
  for (const auto& value : rows.at("qdot")) {
    const double speed = std::fabs(std::stod(value)) * gap_per_rate;
    slowest = std::min(slowest, speed);
    fastest = std::max(fastest, speed);
  }
  EXPECT_GT(slowest, 0.8 * fastest);  // one orbit at every value (c√|μ| grows tenfold over them)
  EXPECT_GT(slowest, 3.0 * c * std::sqrt(1e-5));  // far above c√|μ| near the graze
}

}  // namespace
