#include "support/test_support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>
#include <thread>

#include <impactlab/platform/run_program.hpp>

extern char** environ;

namespace impactlab::testing {

namespace fs = std::filesystem;

ScratchFolder::ScratchFolder() {
  std::string name = (fs::temp_directory_path() / "impactlab_test_XXXXXX").string();
  if (::mkdtemp(name.data()) == nullptr)
    throw fs::filesystem_error("cannot create a scratch folder", name,
                               std::error_code(errno, std::generic_category()));
  path_ = name;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream cells_in(line);
    std::string cell;
    while (std::getline(cells_in, cell, ',')) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  std::stringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

int count_lines(std::string_view text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

namespace {

// The variable's name of a NAME=VALUE entry.
std::string_view variable_name(std::string_view entry) { return entry.substr(0, entry.find('=')); }

// This process's environment with `additions` (NAME=VALUE) in place of the
// variables of those names.
std::vector<std::string> environment_with(const std::vector<std::string>& additions) {
  std::vector<std::string> entries;
  for (char** variable = environ; *variable != nullptr; ++variable) {
    const std::string_view entry(*variable);
    const bool replaced = std::any_of(additions.begin(), additions.end(), [&](const auto& added) {
      return variable_name(added) == variable_name(entry);
    });
    if (!replaced) entries.emplace_back(entry);
  }
  entries.insert(entries.end(), additions.begin(), additions.end());
  return entries;
}

// The null-terminated array of pointers that argv and envp are.
std::vector<char*> pointers_to(std::vector<std::string>& texts) {
  std::vector<char*> pointers;
  pointers.reserve(texts.size() + 1);
  for (auto& text : texts) pointers.push_back(text.data());
  pointers.push_back(nullptr);
  return pointers;
}

// Runs `words` (words[0] a path, or a name looked up on PATH), standard
// output and error to files of a scratch folder, and waits for it: blocking
// when nothing can end it early, otherwise asking every 2 ms.
ProgramRun run_words(std::vector<std::string> words, const RunSettings& settings) {
  const ScratchFolder capture;
  const fs::path directory = settings.directory.empty() ? capture.path() : settings.directory;
  fs::create_directories(directory);
  const fs::path out_path = capture / "stdout";
  const fs::path err_path = capture / "stderr";
  std::vector<std::string> environment = environment_with(settings.environment);
  const std::vector<char*> argv = pointers_to(words);
  const std::vector<char*> envp = pointers_to(environment);

  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  ::posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ::posix_spawn_file_actions_addchdir_np(&actions, directory.c_str());
  pid_t child = 0;
  const int spawned =
      ::posix_spawnp(&child, argv[0], &actions, nullptr, argv.data(), envp.data());
  ::posix_spawn_file_actions_destroy(&actions);
  ProgramRun run;
  if (spawned != 0) return run;

  const bool limited = std::isfinite(settings.limit_s);
  const bool polled = limited || settings.kill_when;
  const auto deadline =
      std::chrono::steady_clock::now() +
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(limited ? settings.limit_s : 0.0));
  int raw = 0;
  rusage usage{};
  // 1 once the child is reaped (its status in raw), 0 while it runs (WNOHANG),
  // -1 when waiting failed
  const auto reap = [&](int options) {
    while (true) {
      const pid_t done = ::wait4(child, &raw, options, &usage);
      if (done == child) return 1;
      if (done == 0) return 0;
      if (errno != EINTR) return -1;
    }
  };
  int reaped = reap(polled ? WNOHANG : 0);
  while (reaped == 0) {
    run.timed_out = limited && std::chrono::steady_clock::now() > deadline;
    if (run.timed_out || (settings.kill_when && settings.kill_when())) {
      ::kill(child, SIGKILL);
      reaped = reap(0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    reaped = reap(WNOHANG);
  }
  if (reaped == 1) {
    if (WIFEXITED(raw)) run.status = WEXITSTATUS(raw);
    if (WIFSIGNALED(raw)) run.signal = WTERMSIG(raw);
    run.max_rss_kb = usage.ru_maxrss;
  }
  run.out = slurp(out_path);
  run.err = slurp(err_path);
  return run;
}

}  // namespace

ProgramRun run_impactlab(const std::vector<std::string>& arguments, const RunSettings& settings) {
  if (settings.mpi_ranks <= 0) {
    std::vector<std::string> words = {IMPACTLAB_BINARY};
    words.insert(words.end(), arguments.begin(), arguments.end());
    return run_words(std::move(words), settings);
  }
  std::vector<std::string> words = {"mpirun", "-n", std::to_string(settings.mpi_ranks),
                                    "--oversubscribe", IMPACTLAB_BINARY};
  words.insert(words.end(), arguments.begin(), arguments.end());
  RunSettings ranks = settings;
  ranks.environment.insert(ranks.environment.end(),
                           {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                            "OMPI_MCA_rmaps_base_oversubscribe=1"});
#if defined(__SANITIZE_ADDRESS__)
  ranks.environment.push_back(
      "ASAN_OPTIONS=detect_leaks=0:abort_on_error=0:strict_string_checks=1");
#endif
  return run_words(std::move(words), ranks);
}

ProgramRun run_command_line(std::string_view command_line, const RunSettings& settings) {
  return run_impactlab(split_on_spaces(command_line), settings);
}

bool mpirun_found() {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path != nullptr ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');)
    if (!folder.empty() && ::access((fs::path(folder) / "mpirun").c_str(), X_OK) == 0) return true;
  return false;
}

::testing::AssertionResult refused_naming(const ProgramRun& run, std::string_view key) {
  constexpr std::string_view program = "impactlab: ";
  const std::string_view line(run.err);
  const std::string_view message =
      line.starts_with(program) ? line.substr(program.size()) : std::string_view{};
  const bool first_word = message.starts_with(key) && message.size() > key.size() &&
                          (message[key.size()] == ' ' || message[key.size()] == ':');
  const bool last_word = message.ends_with(": " + std::string(key) + "\n");
  if (run.status == 2 && count_lines(run.err) == 1 && (first_word || last_word))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected exit status 2 and one line \"" << program << "...\" naming " << key
         << " first or last; got exit status " << run.status << " and:\n" << run.err;
}

}  // namespace impactlab::testing
