// Output files (src/io/output.hpp): the files of a run appear together or not
// at all; a failed run leaves no directory behind; events stream to the file
// as the run goes, so the memory of `simulate` does not grow with its length.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <signal.h>
#include <sys/resource.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

using namespace impactlab::testing;

std::vector<std::string> entries(const std::filesystem::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    names.push_back(entry.path().filename().string());
  return names;
}

// Runs the program for its peak memory (ProgramRun::max_rss_kb). Under
// AddressSanitizer (scripts/test.sh --sanitize) the child runs without the
// allocator's quarantine, which holds every freed block back (256 MB by
// default) and so makes the peak grow with the number of allocations rather
// than with what the program keeps; the peak then measures the program again,
// shadow memory included.
ProgramRun run_measured(const std::vector<std::string>& arguments) {
  RunSettings settings;
#if defined(__SANITIZE_ADDRESS__)
  const char* options = std::getenv("ASAN_OPTIONS");
  settings.environment = {std::string("ASAN_OPTIONS=") + (options != nullptr ? options : "") +
                          ":quarantine_size_mb=0"};
#endif
  return run_impactlab(arguments, settings);
}

TEST(RunFiles, CommitPutsEveryFileInPlace) {
  const ScratchFolder scratch;
  const auto dir = scratch / "commit";
  {
    RunFiles files(dir);
    files.add("a.csv").stream() << "a\n";
    files.add("meta.json").stream() << "{}\n";
    EXPECT_TRUE(entries(dir).size() == 2u);  // the temporaries only
    EXPECT_FALSE(std::filesystem::exists(dir / "a.csv"));
    files.commit();
  }
  EXPECT_EQ(slurp(dir / "a.csv"), "a\n");
  EXPECT_EQ(slurp(dir / "meta.json"), "{}\n");
  EXPECT_EQ(entries(dir).size(), 2u);
}

// A run that stops before its commit (an exception) leaves nothing, not even
// the directory it created.
TEST(RunFiles, WithoutCommitNothingIsLeftBehind) {
  const ScratchFolder scratch;
  const auto dir = scratch / "abandoned" / "out";
  {
    RunFiles files(dir);
    files.add("events.csv").stream() << "t\n1\n";
    EXPECT_TRUE(std::filesystem::is_directory(dir));
  }
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// A directory that existed before is kept, with what it held.
TEST(RunFiles, AnExistingDirectoryIsKept) {
  const ScratchFolder scratch;
  const auto dir = scratch / "existing";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "notes.txt") << "mine\n";
  { RunFiles files(dir); files.add("events.csv").stream() << "t\n"; }
  EXPECT_EQ(entries(dir), std::vector<std::string>{"notes.txt"});
}

// One file that cannot be put in place (its name taken by a directory):
// none of the run's files appears.
TEST(RunFiles, IfOneFileFailsNoneAppears) {
  const ScratchFolder scratch;
  const auto dir = scratch / "one_fails";
  std::filesystem::create_directories(dir / "meta.json");
  RunFiles files(dir);
  files.add("events.csv").stream() << "t\n1\n";
  files.add("trajectory.csv").stream() << "t\n1\n";
  files.add("meta.json").stream() << "{}\n";
  EXPECT_THROW(files.commit(), std::exception);
  EXPECT_FALSE(std::filesystem::exists(dir / "events.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "trajectory.csv"));
}

// Every field reads back to the same double (fmt's shortest round-trip
// form: the fewest digits that do, so 0.1 is written "0.1")
// A run owns its directory. A later run replaces an earlier run's files:
// a sampled run's trajectory.csv used to stay beside a later unsampled run's
// events.csv and meta.json (and scripts/plot_simulation.py drew the old curve
// under the new title). The temporaries of a killed run go too; files of
// other names are the user's.
TEST(RunFiles, ALaterRunReplacesAnEarlierRunsFiles) {
  const ScratchFolder scratch;
  const auto dir = scratch / "reused";
  const ProgramRun sampled = run_impactlab(
      {"simulate", "jin2003", "--periods", "2", "--sample", "0.01", "--quiet", "--out", dir.string()});
  ASSERT_EQ(sampled.status, 0) << sampled.err;
  ASSERT_TRUE(std::filesystem::exists(dir / "trajectory.csv"));
  std::ofstream(dir / "notes.txt") << "mine\n";
  std::ofstream(dir / "events.csv.tmp-999999999") << "t\n";  // a killed run's
  const ProgramRun unsampled =
      run_impactlab({"simulate", "jin2003", "--periods", "2", "--quiet", "--out", dir.string()});
  ASSERT_EQ(unsampled.status, 0) << unsampled.err;
  auto names = entries(dir);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"events.csv", "meta.json", "notes.txt"}));
}

// Two runs into one directory at once cannot mix their files (events.csv of
// one beside meta.json of the other): the directory is locked while a run
// holds it, and a second run is refused at once, naming --out.
TEST(RunFiles, ASecondRunIntoALockedDirectoryIsRefused) {
  const ScratchFolder scratch;
  const auto dir = scratch / "locked";
  {
    RunFiles holder(dir);
    const ProgramRun second =
        run_impactlab({"simulate", "jin2003", "--periods", "2", "--quiet", "--out", dir.string()});
    EXPECT_TRUE(refused_naming(second, "--out"));
    EXPECT_NE(second.err.find("another impactlab run"), std::string::npos) << second.err;
    EXPECT_THROW({ RunFiles second(dir); }, BadInput);  // in one process too
  }
  const ProgramRun after =
      run_impactlab({"simulate", "jin2003", "--periods", "2", "--quiet", "--out", dir.string()});
  EXPECT_EQ(after.status, 0) << after.err;
}

// SIGINT or SIGTERM in the middle of a run: the program ends on the signal as
// before, and removes its temporaries first (it left events.csv.tmp-<pid> of
// several MB behind).
TEST(RunFiles, AnInterruptedRunLeavesNoTemporaries) {
  for (const int signal_number : {SIGINT, SIGTERM}) {
    const ScratchFolder scratch;
    const auto dir = scratch / "interrupted";
    bool sent = false;
    // once the run's temporary holds rows, the signal to the process its name gives
    const auto interrupt = [&] {
      std::error_code error;
      if (sent || !std::filesystem::is_directory(dir, error)) return false;
      for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
        const std::string name = entry.path().filename().string();
        const std::size_t tag = name.find(".tmp-");
        if (tag == std::string::npos || entry.file_size(error) < 100000) continue;
        ::kill(static_cast<pid_t>(std::stol(name.substr(tag + 5))), signal_number);
        sent = true;
      }
      return false;
    };
    const ProgramRun run =
        run_impactlab({"simulate", "jin2003", "--periods", "5000000", "--quiet", "--set",
                       "limits.max_steps=1e12", "--out", dir.string()},
                      {.limit_s = 120, .kill_when = interrupt});
    ASSERT_TRUE(sent) << run.err;
    EXPECT_FALSE(run.timed_out);
    EXPECT_EQ(run.signal, signal_number) << run.status << ": " << run.err;
    EXPECT_EQ(entries(dir), std::vector<std::string>{});
  }
}

// A text field that needs quoting (a mode named after a model file's wall)
// is quoted as RFC 4180 says, so each row keeps its four fields; one that
// needs none is written as it was.
TEST(TrajectoryCsvWriter, QuotesAModeThatNeedsIt) {
  const ScratchFolder scratch;
  const auto path = scratch / "trajectory.csv";
  {
    AtomicFile file(path);
    TrajectoryCsvWriter writer(file);
    writer.write({0.5, 1.0, 2.0, "stuck_a,b\nc\"d"});
    writer.write({1.5, 1.0, 2.0, "free"});
    file.commit();
  }
  EXPECT_EQ(slurp(path), "t,q,qdot,mode\n0.5,1,2,\"stuck_a,b\nc\"\"d\"\n1.5,1,2,free\n");
}

TEST(EventsCsvWriter, WritesEachEventWithAllItsDigits) {
  const ScratchFolder scratch;
  const auto dir = scratch / "writer";
  RunFiles files(dir);
  AtomicFile& file = files.add("events.csv");
  EventsCsvWriter writer(file);
  EventRecord impact{0.1, EventKind::impact, 1, 0.07142857142857142, -1.0 / 3.0, 0.1};
  writer.write(impact);
  EventRecord accumulation{1.5, EventKind::accumulation, -1, -0.25, 0.0, 0.0};
  accumulation.accumulation_error = 2.5e-14;
  writer.write(accumulation);
  files.commit();
  std::istringstream text(slurp(dir / "events.csv"));
  std::string header, first, second;
  std::getline(text, header);
  std::getline(text, first);
  std::getline(text, second);
  EXPECT_EQ(header.rfind("t,kind,wall,q,qdot_before,qdot_after,", 0), 0u);
  EXPECT_NE(header.find(",accumulation_error"), std::string::npos);
  EXPECT_EQ(first.rfind("0.1,impact,1,0.07142857142857142,-0.3333333333333333,0.1,", 0), 0u) << first;
  EXPECT_EQ(first.back(), ',');  // not computed: empty
  EXPECT_EQ(second.substr(second.rfind(',') + 1), "2.5e-14");
  // read back, bit for bit
  std::vector<std::string> fields;
  std::stringstream row(first);
  for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
  ASSERT_GE(fields.size(), 6u);
  EXPECT_EQ(std::stod(fields[0]), impact.t);
  EXPECT_EQ(std::stod(fields[3]), impact.q);
  EXPECT_EQ(std::stod(fields[4]), impact.qdot_before);
  EXPECT_EQ(std::stod(fields[5]), impact.qdot_after);
  EXPECT_EQ(std::stod(second.substr(second.rfind(',') + 1)), accumulation.accumulation_error);
}

// What a model adds to the core's record (io/event_extension.hpp) is asked
// of the extender for each event and written in its own columns; without an
// extender they stay empty.
TEST(EventsCsvWriter, WritesEachEventsExtensionInItsColumns) {
  const ScratchFolder scratch;
  const auto dir = scratch / "writer_extension";
  RunFiles files(dir);
  EventsCsvWriter extended(files.add("extended.csv"), [](const EventRecord& event) {
    return event.kind == EventKind::impact ? EventExtension{0.125, -2.5} : EventExtension{};
  });
  EventsCsvWriter plain(files.add("plain.csv"));
  EventRecord impact{0.1, EventKind::impact, 1, 0.07, -0.5, 0.15};
  EventRecord graze{0.2, EventKind::grazing, -1, -0.07, 0.0, 0.0};
  for (EventsCsvWriter* writer : {&extended, &plain}) {
    writer->write(impact);
    writer->write(graze);
  }
  files.commit();
  const auto rows = [](const std::string& text) {
    std::vector<std::vector<std::string>> table;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
      std::vector<std::string> fields;
      std::stringstream row(line);
      for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
      table.push_back(fields);
    }
    return table;
  };
  const auto with = rows(slurp(dir / "extended.csv")), without = rows(slurp(dir / "plain.csv"));
  ASSERT_EQ(with.size(), 3u);
  ASSERT_EQ(without.size(), 3u);
  ASSERT_GE(with[0].size(), 12u);
  EXPECT_EQ(with[0][10], "instantaneous_residual");
  EXPECT_EQ(with[0][11], "sliding_residual");
  EXPECT_EQ(with[1][10], "0.125");
  EXPECT_EQ(with[1][11], "-2.5");
  EXPECT_EQ(with[2][10], "");  // the graze: not computed
  EXPECT_EQ(without[1][10], "");
  EXPECT_EQ(without[1][11], "");
  // the other columns do not depend on the extension
  EXPECT_EQ(with[0], without[0]);
  for (std::size_t column : {0, 1, 2, 3, 4, 5}) EXPECT_EQ(with[1][column], without[1][column]);
}

// The command line: meta.json cannot be written (its name is a directory),
// so neither events.csv nor anything else of the run appears.
TEST(SimulateFiles, MetaUnwritableMeansNoEventsCsv) {
  const ScratchFolder scratch;
  const auto dir = scratch / "meta_unwritable";
  std::filesystem::create_directories(dir / "meta.json");
  const ProgramRun run = run_impactlab({"simulate", "jin2003", "--periods", "2", "--sample", "0.01",
                                    "--quiet", "--out", dir.string()});
  EXPECT_NE(run.status, 0);
  EXPECT_EQ(entries(dir), std::vector<std::string>{"meta.json"});
}

// An output that cannot be written ends the run with exit status 4 and one
// line naming the file, and leaves no file of the run, temporary or not. A
// file size limit fails the writes as a full disk does (EFBIG, ENOSPC): it
// used to kill the program (SIGXFSZ) with its temporaries left behind, and a
// full disk exited 1.
TEST(OutputFailures, AFullDiskExitsFourAndLeavesNothing) {
  const ScratchFolder scratch;
  const auto dir = scratch / "full";
  std::filesystem::create_directories(dir);
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit limited = saved;
  limited.rlim_cur = 64 * 1024;  // bytes; events.csv of 2000 periods is about 400 kB
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limited), 0);
  const ProgramRun run = run_impactlab(
      {"simulate", "jin2003", "--periods", "2000", "--quiet", "--out", dir.string()});
  ::setrlimit(RLIMIT_FSIZE, &saved);
  EXPECT_EQ(run.signal, 0);
  EXPECT_EQ(run.status, 4) << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("events.csv"), std::string::npos) << run.err;
  EXPECT_EQ(entries(dir), std::vector<std::string>{});
}

// A folder that takes no new file (procfs refuses them even to root, for
// whom a read-only mode bit does not count) exits 4 too, not 1.
TEST(OutputFailures, AReadOnlyFolderExitsFour) {
  const ProgramRun run = run_impactlab(
      {"simulate", "jin2003", "--periods", "2", "--quiet", "--out", "/proc/self/fdinfo"});
  EXPECT_EQ(run.status, 4) << run.err;
  EXPECT_EQ(count_lines(run.err), 1) << run.err;
  EXPECT_NE(run.err.find("/proc/self/fdinfo"), std::string::npos) << run.err;
}

// A run that fails on its input after the directory was named leaves no
// empty --out directory behind.
TEST(SimulateFiles, AFailedRunLeavesNoDirectory) {
  const ScratchFolder scratch;
  const auto dir = scratch / "failed" / "out";
  const ProgramRun run = run_impactlab({"simulate", "jin2003", "--set", "t0=5", "--t-end", "1",
                                    "--quiet", "--out", dir.string()});
  EXPECT_TRUE(refused_naming(run, "--t-end"));
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// Memory that does not grow with the run: ten times the run length (about
// 1.1 k and 11 k events at V0 = 1.5 m/s) within 10 % of the same peak
// (about 9.5 MB). Held in memory at 190 bytes per event, the longer run's
// events alone would add about 2 MB, over 20 %.
TEST(SimulateFiles, PeakMemoryDoesNotGrowWithTheRunLength) {
  const ScratchFolder scratch;
  const auto short_dir = scratch / "memory_short";
  const auto long_dir = scratch / "memory_long";
  const ProgramRun short_run = run_measured(
      {"simulate", "jin2003", "--t-end", "1e3", "--quiet", "--out", short_dir.string()});
  const ProgramRun long_run = run_measured(
      {"simulate", "jin2003", "--t-end", "1e4", "--quiet", "--out", long_dir.string()});
  ASSERT_EQ(short_run.status, 0);
  ASSERT_EQ(long_run.status, 0);
  const auto meta_short = nlohmann::json::parse(slurp(short_dir / "meta.json"));
  const auto meta_long = nlohmann::json::parse(slurp(long_dir / "meta.json"));
  const auto events_short = meta_short["counts"]["events"].get<std::uint64_t>();
  const auto events_long = meta_long["counts"]["events"].get<std::uint64_t>();
  EXPECT_GT(events_long, 5 * events_short);
  // every event is in the file: one row each after the header
  std::ifstream in(long_dir / "events.csv");
  std::uint64_t rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, events_long + 1);
  EXPECT_LE(static_cast<double>(long_run.max_rss_kb), 1.10 * static_cast<double>(short_run.max_rss_kb))
      << "peak memory " << short_run.max_rss_kb << " KiB at t-end 1e3, " << long_run.max_rss_kb
      << " KiB at 1e4";
}


// The same for a long Poincaré record: 30 times the points (the linear
// impact oscillator's strobe, exact flow) within 10 % of the same peak. Held
// in memory at 32 bytes a point, 3e5 points alone would add 9.6 MB.
TEST(PoincareFiles, PeakMemoryDoesNotGrowWithThePointCount) {
  const ScratchFolder scratch;
  const auto short_dir = scratch / "poincare_memory_short";
  const auto long_dir = scratch / "poincare_memory_long";
  const ProgramRun short_run =
      run_measured({"poincare", "linear_impact", "--points", "10000", "--transient", "10",
                   "--quiet", "--out", short_dir.string()});
  const ProgramRun long_run =
      run_measured({"poincare", "linear_impact", "--points", "300000", "--transient", "10",
                   "--quiet", "--out", long_dir.string()});
  ASSERT_EQ(short_run.status, 0);
  ASSERT_EQ(long_run.status, 0);
  std::ifstream in(long_dir / "poincare.csv");
  std::uint64_t rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 300000u + 1);
  const auto meta_long = nlohmann::json::parse(slurp(long_dir / "meta.json"));
  EXPECT_EQ(meta_long["counts"]["points"].get<std::uint64_t>(), 300000u);
  EXPECT_LE(static_cast<double>(long_run.max_rss_kb), 1.10 * static_cast<double>(short_run.max_rss_kb))
      << "peak memory " << short_run.max_rss_kb << " KiB at 1e4 points, " << long_run.max_rss_kb
      << " KiB at 3e5";
}

// A 1D sweep writes bifurcation.csv from its checkpoint lines record by
// record: 30 times more parameter values (and section points) must not raise
// the peak memory, and every point must reach the file.
TEST(SweepFiles, PeakMemoryDoesNotGrowWithTheNumberOfValues) {
  const ScratchFolder scratch;
  const auto short_dir = scratch / "sweep_memory_short";
  const auto long_dir = scratch / "sweep_memory_long";
  const ProgramRun short_run =
      run_measured({"sweep", "linear_impact", "--param", "omega=2.0:2.2:4", "--points", "3000",
                   "--transient", "10", "--quiet", "--out", short_dir.string()});
  const ProgramRun long_run =
      run_measured({"sweep", "linear_impact", "--param", "omega=2.0:2.2:120", "--points", "3000",
                   "--transient", "10", "--quiet", "--out", long_dir.string()});
  ASSERT_EQ(short_run.status, 0);
  ASSERT_EQ(long_run.status, 0);
  std::ifstream in(long_dir / "bifurcation.csv");
  std::uint64_t rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 120u * 3000u + 1);
  EXPECT_LE(static_cast<double>(long_run.max_rss_kb), 1.10 * static_cast<double>(short_run.max_rss_kb))
      << "peak memory " << short_run.max_rss_kb << " KiB at 4 values, " << long_run.max_rss_kb
      << " KiB at 120";
}

}  // namespace
}  // namespace impactlab
