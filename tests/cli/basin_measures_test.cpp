// Basin measures from the command line (`impactlab basins`, meta.json's
// "basin_measures"; the measures themselves are checked against closed forms
// in tests/analysis/basin_measures_test.cpp): on the shipped bouncing ball's
// basins at Γ = Aω²/g = 0.9, where rest on the table and bouncing orbits
// coexist, every measure is there, finite and in its range
// (0 ≤ S ≤ ln(labels), α > 0, d = 2 − α), the box is 5 × 5, the scales are
// 1, 2, 4 (a quarter of the 20-point side), and the CLI prints them in one
// line after its summary; a box larger than the grid is refused, naming the
// option.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

const std::string bouncing_ball_basins =
    "basins bouncing_ball --set A=0.00981 --x initial.y=0:0.1:30 --y initial.y_dot=-1:1:20 "
    "--threads 2";

TEST(BasinMeasuresCli, BouncingBallBasinsHaveTheMeasuresInMeta) {
  const ScratchFolder scratch;
  const fs::path out = scratch / "basins";
  const ProgramRun run = run_command_line(bouncing_ball_basins + " --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  const auto meta = nlohmann::json::parse(slurp(out / "meta.json"));
  ASSERT_TRUE(meta.contains("basin_measures")) << meta.dump(2);
  const auto& m = meta["basin_measures"];
  EXPECT_EQ(m["box_size"], 5);
  EXPECT_EQ(m["boxes"], (30 / 5) * (20 / 5));
  const int labels = m["labels"];
  EXPECT_GE(labels, 2);  // rest and bouncing at least
  const double most = std::log(static_cast<double>(labels));
  for (const char* entropy : {"basin_entropy", "boundary_basin_entropy"}) {
    ASSERT_TRUE(m[entropy].is_number()) << entropy;
    EXPECT_GE(m[entropy].get<double>(), 0.0) << entropy;
    EXPECT_LE(m[entropy].get<double>(), most + 1e-12) << entropy;
  }
  EXPECT_GT(m["boundary_boxes"].get<int>(), 0);
  EXPECT_LE(m["boundary_boxes"].get<int>(), m["boxes"].get<int>());
  EXPECT_LE(m["basin_entropy"].get<double>(), m["boundary_basin_entropy"].get<double>());
  EXPECT_EQ(m["boundary_is_fractal_by_log2"].get<bool>(),
            m["boundary_basin_entropy"].get<double>() > std::log(2.0));
  EXPECT_EQ(m["scales"], nlohmann::json({1, 2, 4}));
  ASSERT_EQ(m["uncertain_fraction"].size(), 3u);
  for (const auto& f : m["uncertain_fraction"]) {
    EXPECT_GT(f.get<double>(), 0.0);
    EXPECT_LE(f.get<double>(), 1.0);
  }
  ASSERT_TRUE(m["uncertainty_exponent"].is_number());
  ASSERT_TRUE(m["uncertainty_exponent_error"].is_number());
  const double alpha = m["uncertainty_exponent"];
  EXPECT_GT(alpha, 0.0);
  EXPECT_GE(m["uncertainty_exponent_error"].get<double>(), 0.0);
  EXPECT_NEAR(m["boundary_dimension"].get<double>(), 2.0 - alpha, 1e-12);
  EXPECT_TRUE(m["meaning"].contains("basin_entropy"));
  // the one line after the summary
  EXPECT_NE(run.out.find("basin entropy S_b = "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("uncertainty exponent alpha = "), std::string::npos) << run.out;
}

TEST(BasinMeasuresCli, ABoxLargerThanTheGridIsRefusedNamingTheOption) {
  for (const std::string box : {"5", "0"}) {
    const ScratchFolder scratch;
    const ProgramRun run = run_command_line(
        "basins bouncing_ball --x initial.y=0:0.1:6 --y initial.y_dot=-1:1:4 --entropy-box " +
        box + " --out " + (scratch / "out").string());
    EXPECT_TRUE(refused_naming(run, "--entropy-box")) << box << ": " << run.err;
    EXPECT_FALSE(fs::exists(scratch / "out" / "basins.csv"));
  }
}

}  // namespace
