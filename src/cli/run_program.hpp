// Runs an external program (the Python plot scripts, bench's SciPy event loop)
// from an argument vector, without a shell: a path or any other argument is
// passed as data and is never parsed as shell text.
#pragma once

#include <string>
#include <vector>

namespace impactlab::cli {

// What happens to the program's standard output and error.
enum class ProgramOutput {
  inherit,      // shared with impactlab
  discard,      // /dev/null
  discard_stdout,  // standard output to /dev/null, errors shown
};

// Runs arguments[0] (looked up on PATH when it has no '/') with the whole
// vector as its argv, waits for it, and returns its exit status; -1 when it
// could not be started or ended on a signal.
int run_program(const std::vector<std::string>& arguments,
                ProgramOutput output = ProgramOutput::inherit);

// The arguments joined with spaces, for messages (not for a shell).
std::string describe_program(const std::vector<std::string>& arguments);

}  // namespace impactlab::cli
