// A sweep's checkpoint files read back: checkpoint-<rank>.jsonl in the output
// directory, one per MPI rank, each a header line naming the sweep and then
// one line per finished point (to_json_line). `impactlab sweep` writes them as
// it goes, resumes from them (--resume) and, at the end, writes
// bifurcation.csv from them one record at a time, so that the section points
// of the whole sweep never sit in memory together.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <impactlab/analysis/sweep.hpp>
#include <impactlab/api/sweep_job.hpp>

namespace impactlab {

// the checkpoint file of one MPI rank
std::string sweep_checkpoint_name(int rank);

// One checkpoint line: the record's JSON (to_json_line) with a last member
// "checksum", the FNV-1a 64-bit hash of the JSON without it, in 16 hex
// digits. A line whose checksum does not match was edited or damaged:
// SweepCheckpoints refuses it rather than let it change the sweep's files.
std::string sweep_checkpoint_line(const SweepRecord& record);

class SweepCheckpoints {
 public:
  // Indexes every checkpoint file in `directory` whose first line is `header`
  // (files of another sweep, and a last line cut short by a kill, are passed
  // over). A complete line whose checksum does not match throws BadInput
  // (key `checkpoint`, value FILE:LINE). `keep_points` false: records()
  // holds the records without their points.
  SweepCheckpoints(const std::filesystem::path& directory, const std::string& header,
                   bool keep_points);

  // the finished records found, by key
  const std::map<SweepRecordKey, SweepRecord>& records() const { return records_; }

  // The record `key` with its section points, read from its line again.
  // Throws std::runtime_error if no checkpoint holds it.
  SweepRecord load(const SweepRecordKey& key) const;

 private:
  struct Place {
    std::size_t file = 0;      // index into files_
    std::uint64_t offset = 0;  // byte offset of the record's line
  };
  std::vector<std::filesystem::path> files_;
  std::map<SweepRecordKey, Place> places_;
  std::map<SweepRecordKey, SweepRecord> records_;
};

}  // namespace impactlab
