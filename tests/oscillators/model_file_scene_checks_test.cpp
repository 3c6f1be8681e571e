// A model file gets the built-in scenes' checks before it runs: an initial
// state inside a wall (once a no_progress stop at t = 0, exit 3) and a
// restitution outside [0, 1] (once accepted) exit 2 naming the key.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab::testing;

// a mass on a spring below a stop at x = 1
std::string model_text(const std::string& restitution, const std::string& parameters = "") {
  return "[initial]\nx = 0.5\n[model]\nstates = [\"x\", \"v\"]\nforcing_frequency = \"1\"\n"
         "[model.parameters]\nk = 1.0\n" + parameters +
         "[model.rhs]\nx = \"v\"\nv = \"-k*x + cos(t)\"\n"
         "[[model.walls]]\nname = \"stop\"\nwitness = \"1 - x\"\ndirection = \"falling\"\n"
         "reset = { velocity = \"v\", restitution = \"" + restitution + "\", position = \"x\" }\n";
}

ProgramRun simulate(const ScratchFolder& scratch, const std::string& text,
                    const std::vector<std::string>& extra = {}) {
  const fs::path path = scratch / "model.toml";
  std::ofstream(path) << text;
  std::vector<std::string> arguments = {"simulate", path.string(), "--periods", "2", "--quiet",
                                        "--out", (scratch / "out").string()};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  return run_impactlab(arguments,
                       {.environment = {"IMPACTLAB_CACHE_DIR=" + (scratch / "cache").string()}});
}

TEST(ModelFileSceneChecks, AnInitialStateInsideAWallIsRefused) {
  const ScratchFolder scratch;
  const ProgramRun run = simulate(scratch, model_text("0.8"), {"--set", "initial.x=1.5"});
  EXPECT_TRUE(refused_naming(run, "initial.x")) << run.err;
  EXPECT_NE(run.err.find("inside wall 'stop'"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(scratch / "out" / "events.csv"));
}

TEST(ModelFileSceneChecks, ARestitutionOutsideZeroToOneIsRefused) {
  const ScratchFolder written;
  const ProgramRun literal = simulate(written, model_text("1.7"));
  EXPECT_TRUE(refused_naming(literal, "model.walls[0].reset.restitution")) << literal.err;
  // a parameter without a range of its own: named as the parameter
  const ScratchFolder parameter;
  const ProgramRun named = simulate(parameter, model_text("r", "r = 0.8\n"), {"--set", "r=1.7"});
  EXPECT_TRUE(refused_naming(named, "r")) << named.err;
}

TEST(ModelFileSceneChecks, AStateOnTheFreeSideRuns) {
  const ScratchFolder scratch;
  const ProgramRun run = simulate(scratch, model_text("r", "r = 0.8\n"), {"--set", "r=1"});
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(fs::exists(scratch / "out" / "events.csv"));
}

}  // namespace
