// Runs an external program (the C compiler of model files, the Python plot
// scripts, bench's SciPy event loop) from an argument vector, without a shell:
// a path or any other argument is passed as data and is never parsed as shell
// text (no quoting, no globbing, no command substitution).
//
// Layer 1 (platform services, below every other folder): the oscillators'
// model compiler and the command line both use it.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace impactlab {

// What happens to the program's standard output and error.
enum class ProgramOutput {
  inherit,         // shared with impactlab
  discard,         // /dev/null
  discard_stdout,  // standard output to /dev/null, errors shown
};

// Runs arguments[0] (looked up on PATH when it has no '/') with the whole
// vector as its argv, waits for it, and returns its exit status; -1 when it
// could not be started or ended on a signal.
int run_program(const std::vector<std::string>& arguments,
                ProgramOutput output = ProgramOutput::inherit);

// The same, with standard output and error both written to the file at
// `log_path` (created or truncated); -1 also when that file cannot be opened.
// With a finite `limit_s` (seconds) the program and every process it starts
// are killed once it has run that long, and the status is -2.
int run_program_logged(const std::vector<std::string>& arguments, const std::string& log_path,
                       double limit_s = std::numeric_limits<double>::infinity());

// The arguments joined with spaces, for messages (not for a shell).
std::string describe_program(const std::vector<std::string>& arguments);

// A command given as one string (an environment variable such as
// $IMPACTLAB_CC = "gcc -march=native") split on spaces into an argument
// vector: no quotes, no escapes, runs of spaces count as one.
std::vector<std::string> split_on_spaces(std::string_view command);

}  // namespace impactlab
