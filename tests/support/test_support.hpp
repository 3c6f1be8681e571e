// What the tests share: scratch folders, running the built impactlab program
// from an argument vector (no shell, so that any byte of an argument reaches
// it as data) and collecting how it ended and what it wrote, reading a whole
// file or a text's lines, and the checks of bad input: which key a refusal
// names.
#pragma once

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/io/bad_input.hpp>

// A test file's own names (helpers, constants, its tests) live in namespace
// IMPACTLAB_TEST_FILE_SCOPE. The test programs are unity builds
// (tests/CMakeLists.txt): several test files compiled as one unit, each
// with its own value of this name, so that one file's helpers are never
// found, or overloaded, from another. Compiled alone, a file's names are in
// the anonymous namespace.
#ifndef IMPACTLAB_TEST_FILE_SCOPE
#define IMPACTLAB_TEST_FILE_SCOPE
#endif

namespace impactlab::testing {

// A new, empty folder under the system's temporary directory, removed with
// everything in it when this object goes out of scope. Each one has a name of
// its own, so test processes that CTest runs in parallel never share one.
class ScratchFolder {
 public:
  ScratchFolder();
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  // a path inside the folder (nothing is created)
  [[nodiscard]] std::filesystem::path operator/(const std::filesystem::path& name) const {
    return path_ / name;
  }

 private:
  std::filesystem::path path_;
};

// The whole content of a file; empty when it cannot be read.
std::string slurp(const std::filesystem::path& path);
// A CSV file's rows split at commas (no quoting), the header first; a
// trailing comma is an empty last field.
std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path);

// The lines of a text, without their line breaks.
std::vector<std::string> split_lines(std::string_view text);

// The number of line breaks in a text.
int count_lines(std::string_view text);

// How a run of a program ended, and what it wrote.
struct ProgramRun {
  int status = -1;         // exit status; -1 when it did not start, ended on a signal or was killed
  int signal = 0;          // the signal that ended it, 0 if none
  bool timed_out = false;  // killed after the time limit
  long max_rss_kb = 0;     // its peak resident memory (KiB)
  std::string out, err;    // its standard output and standard error
};

// Where and how the program runs. Its standard input is /dev/null.
struct RunSettings {
  // the working directory (created if missing); empty: a scratch folder of the run's own
  std::filesystem::path directory{};
  // NAME=VALUE entries added to the test's own environment (replacing a variable of that name)
  std::vector<std::string> environment{};
  // seconds after which the program is killed (SIGKILL)
  double limit_s = std::numeric_limits<double>::infinity();
  // asked every 2 ms while the program runs; the program is killed (SIGKILL)
  // once it returns true
  std::function<bool()> kill_when{};
  // above 0: the program runs as that many OpenMPI ranks (mpirun -n). OpenMPI
  // refuses to run as root unless told, and several ranks on a small machine
  // need oversubscription; the variables set for that do nothing otherwise.
  // Under AddressSanitizer the ranks' leak check is off: OpenMPI loads and
  // unloads its components at run time, and what they leave is reported from
  // an "<unknown module>" that no library-name suppression
  // (scripts/lsan_suppressions.txt) can match. Every other check stays on.
  int mpi_ranks = 0;
};

// Runs the impactlab program of this build with `arguments`, waits for it to
// end and returns its status and output.
ProgramRun run_impactlab(const std::vector<std::string>& arguments,
                         const RunSettings& settings = {});

// run_impactlab with the arguments written in `command_line`, separated by
// spaces (as typed at a shell, without its quoting: no argument holds a space).
ProgramRun run_command_line(std::string_view command_line, const RunSettings& settings = {});

// Whether mpirun is on PATH.
bool mpirun_found();

// A run refused for bad input as the program promises it: exit status 2 and
// one line on standard error, "impactlab: " and a message whose subject is
// `key`: its first word, as in "KEY = VALUE: reason" (a key or option the
// library refused), "KEY: reason" (an option the command line's parser
// refused) and "KEY is required", or its last, as in "The following argument
// was not expected: KEY".
::testing::AssertionResult refused_naming(const ProgramRun& run, std::string_view key);

// The key that the BadInput thrown by `action` names (its message is "KEY =
// VALUE: reason"), or "(no BadInput)" when `action` returns: a test compares
// it with the key it expects. Any other exception passes through.
template <class Action>
std::string bad_input_key(Action&& action) {
  try {
    std::forward<Action>(action)();
  } catch (const BadInput& bad) {
    return bad.key();
  }
  return "(no BadInput)";
}

}  // namespace impactlab::testing
