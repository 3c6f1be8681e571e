// Keys that the scene's model does not read (api/model_keys.hpp), from the
// command line: sweep, basins and continue over one exit with status 2 and one
// line naming the option and the key; `scenes` shows which models read each
// key; `--set` of one warns once on stderr and the run's data files are
// those of the run without it.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

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
  expect_refused(run, "--param", "e_t", "model = paper|rigid");
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
  expect_refused(run, "--param", "e_t", "model = paper|rigid");
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
  expect_refused(run, "--y", "e_t", "model = paper|rigid");
}

// The line of `listing` that lists `key`.
std::string key_line(const std::string& listing, const std::string& key) {
  for (const std::string& line : split_lines(listing))
    if (line.starts_with("  " + key + " ")) return line;
  return "(no line for " + key + ")";
}

TEST(ModelKeysCommandLine, ScenesShowsWhichModelsReadEachKey) {
  const ProgramRun run = run_impactlab({"scenes", "jin2003"});
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(key_line(run.out, "e_t").ends_with("(read by model = paper|rigid)")) << run.out;
  EXPECT_TRUE(key_line(run.out, "radius").ends_with("(read by model = rigid)")) << run.out;
  EXPECT_TRUE(key_line(run.out, "spin").ends_with("(read by model = rigid)")) << run.out;
  // the keys every model reads are not marked; the header names the models
  EXPECT_EQ(key_line(run.out, "mu").find("read by"), std::string::npos) << run.out;
  EXPECT_TRUE(run.out.starts_with("jin2003 (pendulum_walls): key = value [unit] range: help "
                                  "(read by model = ...; unmarked: newton|paper|rigid)\n"))
      << run.out;
  // a scene whose one model reads every key lists them as before
  const ProgramRun linear = run_impactlab({"scenes", "linear_impact"});
  ASSERT_EQ(linear.status, 0) << linear.err;
  EXPECT_EQ(linear.out.find("read by"), std::string::npos) << linear.out;
  EXPECT_TRUE(linear.out.starts_with("linear_impact (linear_impact): key = value [unit] range: "
                                     "help\n"))
      << linear.out;
}

TEST(ModelKeysCommandLine, SetOfAKeyTheModelDoesNotReadWarnsOnceAndChangesNoFile) {
  const ScratchFolder scratch;
  const std::string run_options = " --set V0=4.163 --periods 5 --quiet --out ";
  const ProgramRun plain =
      run_command_line("simulate jin2003" + run_options + (scratch / "plain").string());
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(plain.err, "");
  const ProgramRun set = run_command_line("simulate jin2003 --set e_t=-0.3 --set e_t=-0.2" +
                                          run_options + (scratch / "set").string());
  ASSERT_EQ(set.status, 0) << set.err;
  EXPECT_EQ(set.err,
            "impactlab: warning: e_t = -0.2: model = newton does not read e_t (read by model = "
            "paper|rigid); the value changes nothing\n");
  // the events are those of the run without it, byte for byte
  const std::string events = slurp(scratch / "plain" / "events.csv");
  EXPECT_GT(count_lines(events), 10);
  EXPECT_EQ(slurp(scratch / "set" / "events.csv"), events);
}

TEST(ModelKeysCommandLine, SetOfAKeyTheModelReadsDoesNotWarn) {
  const ScratchFolder scratch;
  for (const std::string sets : {"--set model=paper --set e_t=-0.2", "--set mu=0.3",
                                 "--set e_t=-0.2 --set model=paper"}) {
    const ProgramRun run = run_command_line("simulate jin2003 " + sets +
                                            " --periods 1 --quiet --out " +
                                            (scratch / "run").string());
    EXPECT_EQ(run.status, 0) << sets;
    EXPECT_EQ(run.err, "") << sets;
  }
}

}  // namespace
