#include "io/output.hpp"

#include <cmath>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>
#include <unistd.h>

#include "io/bad_input.hpp"

namespace impactlab {

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)),
      temporary_(path_.string() + fmt::format(".tmp-{}", static_cast<long>(::getpid()))),
      stream_(temporary_) {
  if (!stream_) throw std::runtime_error("cannot write " + temporary_.string());
  stream_.precision(17);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::commit() {
  stream_.flush();
  if (!stream_) throw std::runtime_error("writing " + temporary_.string() + " failed");
  stream_.close();
  std::filesystem::rename(temporary_, path_);
  committed_ = true;
}

void prepare_output_directory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory))
    throw BadInput("--out", directory.string(), "cannot create the output directory");
}

std::string csv_field(double value) {
  if (std::isnan(value)) return "";
  return fmt::format("{:.17g}", value);
}

namespace {

std::string field(double value) { return csv_field(value); }

}  // namespace

void write_events_csv(AtomicFile& file, std::span<const EventRecord> events) {
  auto& out = file.stream();
  out << "t,kind,wall,q,qdot_before,qdot_after,normal_impulse,tangential_velocity,normal_force,"
         "friction_work,instantaneous_residual,sliding_residual,tangential_velocity_after\n";
  for (const auto& e : events) {
    out << field(e.t) << ',' << to_string(e.kind) << ',' << e.wall << ',' << field(e.q) << ','
        << field(e.qdot_before) << ',' << field(e.qdot_after) << ',' << field(e.normal_impulse)
        << ',' << field(e.tangential_velocity) << ',' << field(e.normal_force) << ','
        << field(e.friction_work) << ',' << field(e.instantaneous_residual) << ','
        << field(e.sliding_residual) << ',' << field(e.tangential_velocity_after) << '\n';
  }
}

void write_trajectory_csv(AtomicFile& file, std::span<const TrajectorySample> samples) {
  auto& out = file.stream();
  out << "t,q,qdot,mode\n";
  for (const auto& s : samples)
    out << field(s.t) << ',' << field(s.q) << ',' << field(s.qdot) << ',' << s.mode << '\n';
}

void write_json(AtomicFile& file, const nlohmann::json& document) {
  file.stream() << document.dump(2) << '\n';
}

}  // namespace impactlab
