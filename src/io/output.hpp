// Output files: written under a temporary name and renamed into place only
// when complete, so an interrupted run never leaves a truncated file that
// looks finished. The files of one run are committed together (RunFiles):
// if any of them fails, none appears.
#pragma once

#include <filesystem>
#include <fstream>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <impactlab/core/event_log.hpp>
#include <impactlab/core/event_sink.hpp>
#include <impactlab/io/event_columns.hpp>
#include <impactlab/io/event_extension.hpp>
#include <impactlab/io/run_output.hpp>

namespace impactlab {

// A file that appears at `path` only when commit() is called; otherwise its
// temporary is removed.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return stream_; }
  void commit();  // finish() then publish()

  // the two halves of commit(), for RunFiles: flush, check and close the
  // temporary; rename it into place (both throw OutputError on failure, as
  // the constructor does for a temporary it cannot create)
  void finish();
  void publish();
  // removes the published file again (a run whose other files failed)
  void withdraw();
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_, temporary_;
  std::ofstream stream_;
  bool committed_ = false;
};

// The files of one run in one output directory, committed together.
// The directory is created if needed (BadInput, key `out`, if it cannot).
// commit() finishes every file first and renames them into place only when
// all are complete, in the order they were added (meta.json last, so a
// directory with meta.json holds a complete run); a rename that fails takes
// back those already renamed. Without a commit (an exception, a stopped run
// that writes nothing) every temporary is removed, and a directory this run
// created is removed again when left empty: a failed run leaves nothing.
//
// A run owns its directory. It holds an exclusive lock on it (flock on the
// directory itself, no lock file) from construction to destruction: a second
// run into the same directory is refused at once (BadInput, key `out`), so
// two runs never mix their files. On commit, every file of an impactlab
// output name (output_file_names) that this run does not write is removed,
// with the temporaries that runs killed earlier left there: the directory
// then holds this run's files and no file of an earlier run (a sampled
// run's trajectory.csv beside a later unsampled run's events.csv). Files of
// other names are the user's and are left alone. `lock` false: for the MPI
// ranks of a sweep other than rank 0, which share rank 0's directory and
// commit nothing.
class RunFiles {
 public:
  explicit RunFiles(std::filesystem::path directory, bool lock = true);
  ~RunFiles();
  RunFiles(const RunFiles&) = delete;
  RunFiles& operator=(const RunFiles&) = delete;

  AtomicFile& add(const std::string& name);
  void commit();
  [[nodiscard]] const std::filesystem::path& directory() const { return directory_; }

 private:
  // removes what earlier runs left under impactlab's output names
  void remove_earlier_outputs() const;

  std::filesystem::path directory_;
  std::vector<std::filesystem::path> created_directories_;  // deepest first
  bool committed_ = false;
  int lock_descriptor_ = -1;  // the directory, opened and flock-ed; -1: not locked
  std::vector<std::unique_ptr<AtomicFile>> files_;
};

// The names of the files impactlab commands write into an output directory
// (data, sidecars, plots): what a later run's commit replaces.
std::span<const std::string_view> output_file_names();

// Creates the output directory; BadInput (key `out`) if it cannot.
void prepare_output_directory(const std::filesystem::path& directory);

// events.csv, written row by row as the events happen (an EventSink):
// t,kind,wall,q,qdot_before,qdot_after, then normal_impulse,
// tangential_velocity, normal_force, friction_work, instantaneous_residual,
// sliding_residual (the model's EventExtension, asked of `extender` where it
// is given), tangential_velocity_after, accumulation_error (empty where not
// computed). Numbers with all their digits (round-trip).
class EventsCsvWriter final : public EventSink {
 public:
  // writes the header: the core's columns and `columns` of the model's
  explicit EventsCsvWriter(AtomicFile& file, EventExtender extender = {},
                           EventColumns columns = EventColumns::all());
  void write(const EventRecord& event) override;

 private:
  std::ofstream& out_;
  EventExtender extender_;
  EventColumns columns_;
  fmt::memory_buffer row_;
};

// trajectory.csv (t,q,qdot,mode), written row by row (a SampleSink).
class TrajectoryCsvWriter final : public SampleSink {
 public:
  explicit TrajectoryCsvWriter(AtomicFile& file);  // writes the header
  void write(const TrajectorySample& sample) override;

 private:
  std::ofstream& out_;
  fmt::memory_buffer row_;
};

// The same files from events and samples held in memory.
void write_events_csv(AtomicFile& file, std::span<const EventRecord> events,
                      EventExtender extender = {}, EventColumns columns = EventColumns::all());
void write_trajectory_csv(AtomicFile& file, std::span<const TrajectorySample> samples);

void write_json(AtomicFile& file, const nlohmann::json& document);

// A CSV number with all its digits (round-trips), or an empty field for NaN
// (not computed).
std::string csv_field(double value);

// A CSV text field as RFC 4180 writes it: as it is, unless it holds a comma,
// a double quote or a line break, then between double quotes with each double
// quote doubled (a mode named after a model file's wall "a,b\nc\"d" stays one
// field). Text that needs no quoting is written unchanged.
void append_csv_text(fmt::memory_buffer& row, std::string_view text);

}  // namespace impactlab
