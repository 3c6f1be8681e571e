#include <impactlab/platform/run_program.hpp>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <limits>
#include <thread>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace impactlab {

namespace {

// The status reported for a program killed at its time limit.
constexpr int killed_at_limit = -2;

// Spawns argv with the file actions set up by the caller, waits, returns the
// exit status (-1: not started, or ended on a signal). With a finite
// `limit_s` the program runs in a process group of its own, killed whole
// (a compiler and the passes it starts) once the limit has passed:
// killed_at_limit.
int spawn_and_wait(const std::vector<std::string>& arguments, posix_spawn_file_actions_t& actions,
                   double limit_s = std::numeric_limits<double>::infinity()) {
  std::vector<std::string> owned = arguments;
  std::vector<char*> argv;
  argv.reserve(owned.size() + 1);
  for (auto& argument : owned) argv.push_back(argument.data());
  argv.push_back(nullptr);

  const bool limited = std::isfinite(limit_s);
  posix_spawnattr_t attributes;
  ::posix_spawnattr_init(&attributes);
  if (limited) {
    ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    ::posix_spawnattr_setpgroup(&attributes, 0);
  }
  pid_t child = 0;
  const int spawned = ::posix_spawnp(&child, argv[0], &actions, &attributes, argv.data(), environ);
  ::posix_spawnattr_destroy(&attributes);
  if (spawned != 0) return -1;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limited ? limit_s : 0.0);
  for (;;) {
    const pid_t ended = ::waitpid(child, &status, limited ? WNOHANG : 0);
    if (ended == child) break;
    if (ended < 0 && errno != EINTR) return -1;
    if (limited && ended == 0) {
      if (std::chrono::steady_clock::now() >= deadline) {
        ::kill(-child, SIGKILL);
        while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
        }
        return killed_at_limit;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

int run_program(const std::vector<std::string>& arguments, ProgramOutput output) {
  if (arguments.empty()) return -1;
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  if (output != ProgramOutput::inherit)
    ::posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (output == ProgramOutput::discard)
    ::posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  const int status = spawn_and_wait(arguments, actions);
  ::posix_spawn_file_actions_destroy(&actions);
  return status;
}

int run_program_logged(const std::vector<std::string>& arguments, const std::string& log_path,
                       double limit_s) {
  if (arguments.empty()) return -1;
  // opened here rather than by the file actions, so that a log that cannot be
  // written is reported as such and not as the program failing to start
  const int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) return -1;
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawn_file_actions_adddup2(&actions, log, STDOUT_FILENO);
  ::posix_spawn_file_actions_adddup2(&actions, log, STDERR_FILENO);
  const int status = spawn_and_wait(arguments, actions, limit_s);
  ::posix_spawn_file_actions_destroy(&actions);
  ::close(log);
  return status;
}

std::string describe_program(const std::vector<std::string>& arguments) {
  std::string text;
  for (const auto& argument : arguments) text += (text.empty() ? "" : " ") + argument;
  return text;
}

std::vector<std::string> split_on_spaces(std::string_view command) {
  std::vector<std::string> words;
  std::size_t start = 0;
  while (start < command.size()) {
    const std::size_t space = command.find(' ', start);
    const std::size_t end = space == std::string_view::npos ? command.size() : space;
    if (end > start) words.emplace_back(command.substr(start, end - start));
    start = end + 1;
  }
  return words;
}

}  // namespace impactlab
