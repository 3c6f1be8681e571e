// Test support: runs the impactlab program from an argument vector (no shell,
// so that any byte of an argument reaches it as data), with a time limit, and
// collects its exit status, the signal that ended it, and its output.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace impactlab::testing {

struct ProgramRun {
  int status = -1;         // exit status; -1 when it ended on a signal or timed out
  int signal = 0;          // the signal that ended it, 0 if none
  bool timed_out = false;  // killed after the time limit
  std::string out, err;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `program arguments...` in `directory` (created), stdout and stderr to
// files there, stdin from /dev/null; kills it after `limit_s` seconds.
inline ProgramRun run_binary(const std::vector<std::string>& arguments,
                             const std::filesystem::path& directory, double limit_s = 60.0,
                             const std::string& program = IMPACTLAB_BINARY) {
  std::filesystem::create_directories(directory);
  const auto out_path = directory / ".stdout";
  const auto err_path = directory / ".stderr";
  std::vector<std::string> owned = {program};
  owned.insert(owned.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& argument : owned) argv.push_back(argument.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  // run in `directory`: a relative --out lands there
  posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());
  pid_t child = 0;
  const int spawned = posix_spawn(&child, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ProgramRun run;
  if (spawned != 0) return run;

  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  int raw = 0;
  while (true) {
    const pid_t done = waitpid(child, &raw, WNOHANG);
    if (done == child) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(child, SIGKILL);
      waitpid(child, &raw, 0);
      run.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!run.timed_out) {
    if (WIFEXITED(raw)) run.status = WEXITSTATUS(raw);
    if (WIFSIGNALED(raw)) run.signal = WTERMSIG(raw);
  }
  run.out = read_text(out_path);
  run.err = read_text(err_path);
  std::filesystem::remove(out_path);
  std::filesystem::remove(err_path);
  return run;
}

inline int count_lines(const std::string& text) {
  int lines = 0;
  for (const char c : text) lines += c == '\n';
  return lines;
}

}  // namespace impactlab::testing
