// Output files: written under a temporary name and renamed into place only
// when complete, so an interrupted run never leaves a truncated file that
// looks finished.
#pragma once

#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "core/event_log.hpp"
#include "io/run_output.hpp"

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
  void commit();  // flushes, checks, renames; throws std::runtime_error on failure

 private:
  std::filesystem::path path_, temporary_;
  std::ofstream stream_;
  bool committed_ = false;
};

// Creates the output directory; BadInput (key --out) if it cannot.
void prepare_output_directory(const std::filesystem::path& directory);

// events.csv: t,kind,wall,q,qdot_before,qdot_after, then normal_impulse,
// tangential_velocity, normal_force, friction_work, tangential_velocity_after
// (empty where not computed).
void write_events_csv(AtomicFile& file, std::span<const EventRecord> events);

// trajectory.csv: t,q,qdot,mode
void write_trajectory_csv(AtomicFile& file, std::span<const TrajectorySample> samples);

void write_json(AtomicFile& file, const nlohmann::json& document);

// A CSV number with all its digits (round-trips), or an empty field for NaN
// (not computed).
std::string csv_field(double value);

}  // namespace impactlab
