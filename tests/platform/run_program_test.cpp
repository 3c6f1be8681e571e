// Running a program from an argument vector (src/platform/run_program.hpp):
// every argument reaches the program as data, whatever shell syntax it holds;
// exit statuses come back; a command string splits on spaces.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/platform/run_program.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using impactlab::run_program;
using impactlab::run_program_logged;
using impactlab::split_on_spaces;
using impactlab::testing::ScratchFolder;
using impactlab::testing::slurp;

TEST(RunProgram, ShellSyntaxInAnArgumentIsPassedAsData) {
  const ScratchFolder dir;
  const fs::path marker = dir / "injected";
  const std::string hostile = "it's; touch " + marker.string() + "; $(touch " + marker.string() +
                              ") `touch " + marker.string() + "` | > \"x\" *";
  const fs::path log = dir / "log";
  ASSERT_EQ(run_program_logged({"printf", "%s", hostile}, log.string()), 0);
  EXPECT_EQ(slurp(log), hostile);
  EXPECT_FALSE(fs::exists(marker));
}

TEST(RunProgram, ExitStatusesAndStartFailuresComeBack) {
  const ScratchFolder dir;
  const fs::path log = dir / "log";
  EXPECT_EQ(run_program({"true"}), 0);
  EXPECT_EQ(run_program({"sh", "-c", "exit 3"}, impactlab::ProgramOutput::discard), 3);
  EXPECT_EQ(run_program({"/nonexistent/program"}), -1);
  EXPECT_EQ(run_program({}), -1);
  // standard error goes to the log too
  EXPECT_EQ(run_program_logged({"sh", "-c", "echo out; echo err >&2; exit 1"}, log.string()), 1);
  EXPECT_EQ(slurp(log), "out\nerr\n");
  EXPECT_EQ(run_program_logged({"true"}, "/nonexistent/dir/log"), -1);
}

TEST(RunProgram, ACommandStringSplitsOnSpaces) {
  EXPECT_EQ(split_on_spaces("cc"), (std::vector<std::string>{"cc"}));
  EXPECT_EQ(split_on_spaces("  gcc  -march=native -O3 "),
            (std::vector<std::string>{"gcc", "-march=native", "-O3"}));
  EXPECT_TRUE(split_on_spaces("   ").empty());
  EXPECT_TRUE(split_on_spaces("").empty());
}

}  // namespace
