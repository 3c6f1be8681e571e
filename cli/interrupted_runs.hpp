// SIGINT and SIGTERM end the program as they always did, after removing the
// temporaries its outputs are being written under (AtomicFile's
// NAME.tmp-<pid>, src/io/output.hpp): an interrupted run leaves no part of
// itself, where it used to leave events.csv.tmp-<pid> files of several MB.
// The process-wide state this needs (the output directories, the signal
// handler's pipe) lives here, in the program, not in the library.
#pragma once

#include <filesystem>

#include <impactlab/io/output.hpp>

namespace impactlab::cli {

// Installs the handlers and starts the thread that cleans up; call once, at
// the start of main. The handler itself only writes the signal's number to a
// pipe (async-signal-safe); the thread reads it, removes this process's
// temporaries from the directories opened so far, and ends the process with
// the same signal (its default action), so the exit status still says which.
void remove_temporaries_on_interrupt();

// The run's files in `directory` (RunFiles, locked unless `lock` is false),
// the directory watched for temporaries to remove on SIGINT or SIGTERM.
RunFiles open_run_files(const std::filesystem::path& directory, bool lock = true);

}  // namespace impactlab::cli
