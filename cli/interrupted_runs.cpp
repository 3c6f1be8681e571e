#include "interrupted_runs.hpp"

#include <csignal>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

namespace impactlab::cli {

namespace {

// the output directories opened by this process, and their guard
std::mutex watched_mutex;
std::vector<std::filesystem::path> watched_directories;

// the pipe from the signal handler (write end) to the cleaning thread
int signal_pipe[2] = {-1, -1};

extern "C" void forward_signal(int signal_number) {
  const auto byte = static_cast<unsigned char>(signal_number);
  [[maybe_unused]] const ssize_t written = ::write(signal_pipe[1], &byte, 1);
}

// removes every NAME.tmp-<this pid> from the watched directories
void remove_own_temporaries() {
  const std::string suffix = fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  std::lock_guard lock(watched_mutex);
  for (const auto& directory : watched_directories) {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error))
      if (entry.path().filename().string().ends_with(suffix))
        std::filesystem::remove(entry.path(), error);
  }
}

}  // namespace

void remove_temporaries_on_interrupt() {
  if (::pipe2(signal_pipe, O_CLOEXEC) != 0) return;  // no cleanup, the old behaviour
  std::thread([] {
    unsigned char byte = 0;
    while (::read(signal_pipe[0], &byte, 1) != 1) {
    }
    const int signal_number = byte;
    remove_own_temporaries();
    // end as the signal would have: the default action, delivered to this thread
    std::signal(signal_number, SIG_DFL);
    sigset_t only;
    sigemptyset(&only);
    sigaddset(&only, signal_number);
    ::pthread_sigmask(SIG_UNBLOCK, &only, nullptr);
    std::raise(signal_number);
    ::_exit(128 + signal_number);
  }).detach();
  struct sigaction action {};
  action.sa_handler = forward_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

RunFiles open_run_files(const std::filesystem::path& directory, bool lock) {
  {
    std::lock_guard guard(watched_mutex);
    watched_directories.push_back(directory);
  }
  return RunFiles(directory, lock);
}

}  // namespace impactlab::cli
