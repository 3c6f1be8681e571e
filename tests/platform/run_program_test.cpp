// Running a program from an argument vector (src/platform/run_program.hpp):
// every argument reaches the program as data, whatever shell syntax it holds;
// exit statuses come back; a command string splits on spaces.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/platform/run_program.hpp>

namespace {

namespace fs = std::filesystem;
using impactlab::run_program;
using impactlab::run_program_logged;
using impactlab::split_on_spaces;

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("impactlab_run_program_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(RunProgram, ShellSyntaxInAnArgumentIsPassedAsData) {
  const fs::path dir = scratch();
  const fs::path marker = dir / "injected";
  const std::string hostile = "it's; touch " + marker.string() + "; $(touch " + marker.string() +
                              ") `touch " + marker.string() + "` | > \"x\" *";
  const fs::path log = dir / "log";
  ASSERT_EQ(run_program_logged({"printf", "%s", hostile}, log.string()), 0);
  EXPECT_EQ(slurp(log), hostile);
  EXPECT_FALSE(fs::exists(marker));
}

TEST(RunProgram, ExitStatusesAndStartFailuresComeBack) {
  const fs::path log = scratch() / "log";
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
