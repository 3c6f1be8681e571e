// Keys that the scene's model does not read (api/model_keys.hpp), from the
// command line: sweep, basins and continue over one exit with status 2 and one
// line naming the option and the key; `scenes` shows which models read each
// key; `--set` of one warns once on stderr and the run's data files are
// those of the run without it.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace {

using namespace impactlab::testing;

// `run` refused naming `option`, its line naming `key` and the models that read it.
void expect_refused(const ProgramRun& run, std::string_view option, const std::string& key,
                    const std::string& read_by) {
  EXPECT_TRUE(refused_naming(run, option));
  EXPECT_NE(run.err.find(std::string(option) + " = " + key + ": model = newton does not read " +
                         key + " (read by " + read_by + ")"),
            std::string::npos)
      << run.err;
}

TEST(ModelKeysCommandLine, SweepOfAKeyTheModelDoesNotReadExitsTwoNamingIt) {
  const ScratchFolder scratch;
  const auto out = scratch / "sweep";
  const ProgramRun run =
      run_command_line("sweep jin2003 --param e_t=-0.5:0:3 --quiet --out " + out.string());
  expect_refused(run, "--param", "e_t", "model = paper");
  EXPECT_FALSE(std::filesystem::exists(out / "meta.json"));
}

TEST(ModelKeysCommandLine, SecondAxisOfAMapIsCheckedToo) {
  const ScratchFolder scratch;
  const ProgramRun run = run_command_line(
      "sweep jin2003 --param omega=6:7:2 --param radius=0:0.01:2 --quiet --out " +
      (scratch / "map").string());
  expect_refused(run, "--param", "radius", "model = rigid");
}

TEST(ModelKeysCommandLine, ContinueOverAKeyTheModelDoesNotReadExitsTwoNamingIt) {
  const ScratchFolder scratch;
  const ProgramRun run = run_command_line("continue jin2003 --param e_t=-0.5:0 --quiet --out " +
                                          (scratch / "branch").string());
  expect_refused(run, "--param", "e_t", "model = paper");
}

TEST(ModelKeysCommandLine, ContinueParam2OverAKeyTheModelDoesNotReadExitsTwoNamingIt) {
  const ScratchFolder scratch;
  const ProgramRun run =
      run_command_line("continue jin2003 --param omega=6:7 --param2 radius=0:0.01 --quiet --out " +
                       (scratch / "curve").string());
  expect_refused(run, "--param2", "radius", "model = rigid");
}

TEST(ModelKeysCommandLine, BasinsOverAKeyTheModelDoesNotReadExitsTwoNamingTheAxis) {
  const ScratchFolder scratch;
  const ProgramRun run = run_command_line(
      "basins jin2003 --x initial.theta=-0.05:0.05:3 --y e_t=-0.5:0:3 --quiet --out " +
      (scratch / "basins").string());
  expect_refused(run, "--y", "e_t", "model = paper");
}

}  // namespace
