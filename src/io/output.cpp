#include <impactlab/io/output.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <fmt/compile.h>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/output_error.hpp>

namespace impactlab {

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)),
      temporary_(path_.string() + fmt::format(".tmp-{}", static_cast<long>(::getpid()))),
      stream_(temporary_) {
  if (!stream_)
    throw OutputError("cannot write " + temporary_.string() + ": " + std::strerror(errno));
  stream_.precision(17);
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  stream_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void AtomicFile::finish() {
  // a write that failed on the way (a full disk, a file size limit) leaves
  // the stream failed: errno still says why when the flush is the one
  errno = 0;
  stream_.flush();
  if (!stream_)
    throw OutputError("writing " + temporary_.string() + " failed" +
                      (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()));
  stream_.close();
  if (stream_.fail()) throw OutputError("closing " + temporary_.string() + " failed");
}

void AtomicFile::publish() {
  std::error_code error;
  std::filesystem::rename(temporary_, path_, error);
  if (error)
    throw OutputError("renaming " + temporary_.string() + " to " + path_.filename().string() +
                      " failed: " + error.message());
  committed_ = true;
}

void AtomicFile::withdraw() {
  if (!committed_) return;
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

void AtomicFile::commit() {
  finish();
  publish();
}

RunFiles::RunFiles(std::filesystem::path directory, bool lock)
    : directory_(std::move(directory)) {
  // the levels of the path that do not exist yet, deepest first: a failed
  // run removes exactly these (when empty), so `out/jin2003` leaves no `out`
  std::error_code error;
  for (std::filesystem::path level = directory_; !level.empty() && level != level.parent_path();
       level = level.parent_path()) {
    if (std::filesystem::exists(level, error)) break;
    created_directories_.push_back(level);
  }
  prepare_output_directory(directory_);
  if (!lock) return;
  lock_descriptor_ = ::open(directory_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (lock_descriptor_ < 0)
    throw OutputError("cannot open the output directory " + directory_.string() + ": " +
                      std::strerror(errno));
  if (::flock(lock_descriptor_, LOCK_EX | LOCK_NB) != 0) {
    const int reason = errno;
    ::close(lock_descriptor_);
    lock_descriptor_ = -1;
    if (reason == EWOULDBLOCK)
      throw BadInput("out", directory_.string(),
                     "another impactlab run is writing into this directory");
    throw OutputError("cannot lock the output directory " + directory_.string() + ": " +
                      std::strerror(reason));
  }
}

RunFiles::~RunFiles() {
  if (!committed_) {
    files_.clear();  // removes the temporaries
    std::error_code ignored;
    for (const auto& level : created_directories_) {
      if (!std::filesystem::is_empty(level, ignored)) break;
      std::filesystem::remove(level, ignored);
    }
  }
  if (lock_descriptor_ >= 0) ::close(lock_descriptor_);  // releases the lock
}

AtomicFile& RunFiles::add(const std::string& name) {
  files_.push_back(std::make_unique<AtomicFile>(directory_ / name));
  return *files_.back();
}

namespace {

// Whether `name` is `output` + ".tmp-" + a process id: a temporary of an
// output file (AtomicFile).
bool is_temporary_of(std::string_view name, std::string_view output) {
  if (!name.starts_with(output)) return false;
  const std::string_view rest = name.substr(output.size());
  constexpr std::string_view tag = ".tmp-";
  return rest.size() > tag.size() && rest.starts_with(tag) &&
         std::all_of(rest.begin() + static_cast<std::ptrdiff_t>(tag.size()), rest.end(),
                     [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

void RunFiles::remove_earlier_outputs() const {
  std::vector<std::string> own;
  for (const auto& file : files_) own.push_back(file->path().filename().string());
  std::error_code error;
  std::vector<std::filesystem::path> earlier;
  for (const auto& entry : std::filesystem::directory_iterator(directory_, error)) {
    if (!entry.is_regular_file(error)) continue;
    const std::string name = entry.path().filename().string();
    const auto& names = output_file_names();
    const bool output = std::find(names.begin(), names.end(), name) != names.end();
    const bool replaced = output && std::find(own.begin(), own.end(), name) == own.end();
    // with the directory locked, a temporary is this run's or a killed run's
    const bool stale_temporary =
        std::any_of(names.begin(), names.end(),
                    [&](std::string_view output_name) {
                      return is_temporary_of(name, output_name);
                    }) &&
        !name.ends_with(fmt::format(".tmp-{}", static_cast<long>(::getpid())));
    if (replaced || stale_temporary) earlier.push_back(entry.path());
  }
  if (error)
    throw OutputError("cannot list the output directory " + directory_.string() + ": " +
                      error.message());
  for (const auto& path : earlier) {
    std::filesystem::remove(path, error);
    if (error)
      throw OutputError("cannot remove " + path.string() + ", left by an earlier run: " +
                        error.message());
  }
}

void RunFiles::commit() {
  for (auto& file : files_) file->finish();
  // an unlocked RunFiles (a sweep's other MPI ranks) commits nothing of its own
  if (lock_descriptor_ >= 0) remove_earlier_outputs();
  for (std::size_t i = 0; i < files_.size(); ++i) {
    try {
      files_[i]->publish();
    } catch (...) {
      for (std::size_t j = 0; j < i; ++j) files_[j]->withdraw();
      throw;
    }
  }
  committed_ = true;
}

std::span<const std::string_view> output_file_names() {
  // every command's files (cli/*_command.cpp, api/jin2003_report.cpp) and
  // the plots drawn from them
  static constexpr std::array<std::string_view, 56> names = {
      "meta.json", "events.csv", "trajectory.csv", "simulation.png", "poincare.csv",
      "poincare.png", "bifurcation.csv", "bifurcation.png", "summary.csv", "classes.csv",
      "classes.png", "basins.csv", "basins.png", "attractors.csv", "attractor_points.csv",
      "attractors.png", "samples.csv", "lyapunov.csv", "lyapunov.png", "periodic.json",
      "orbits.csv", "spectrum.csv",
      "branch.csv", "points.csv", "curve.csv", "curve_points.csv", "curve.json", "curve.png",
      "grazing.json", "grazing.png", "continuation.json", "continuation.png",
      "compare.json", "compare.png", "compare_impacts.csv", "compare_contacts.csv",
      "compare_section.csv", "work_precision.csv", "work_precision.json", "summary.md",
      "report.json", "REPORT.md", "fig4a.csv", "fig4a.json", "fig4a.png", "fig4a_values.csv",
      "fig4b.csv", "fig4b.json", "fig4b.png", "fig4b_values.csv", "fig4c.csv", "fig4c.json",
      "fig4c.png", "fig4d.csv", "fig4d.json", "fig4d.png",
  };
  return names;
}

void prepare_output_directory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory))
    throw BadInput("out", directory.string(), "cannot create the output directory");
}

std::string csv_field(double value) {
  if (std::isnan(value)) return "";
  return fmt::format("{:.17g}", value);
}

namespace {

// appends `value` with the fewest digits that read back to the same double
// (fmt's shortest round-trip form, Dragonbox; a 200 000-period jin2003 run
// writing events.csv took 0.88 s against 0.94 s with 17 significant
// digits), or nothing for NaN (not computed)
void append_field(fmt::memory_buffer& row, double value) {
  if (!std::isnan(value)) fmt::format_to(fmt::appender(row), FMT_COMPILE("{}"), value);
}

}  // namespace

void append_csv_text(fmt::memory_buffer& row, std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) {
    row.append(text.data(), text.data() + text.size());
    return;
  }
  row.push_back('"');
  for (char c : text) {
    if (c == '"') row.push_back('"');
    row.push_back(c);
  }
  row.push_back('"');
}

EventsCsvWriter::EventsCsvWriter(AtomicFile& file, EventExtender extender, EventColumns columns)
    : out_(file.stream()), extender_(std::move(extender)), columns_(columns) {
  out_ << columns_.header();
}

void EventsCsvWriter::write(const EventRecord& e) {
  row_.clear();
  auto comma = [this] { row_.push_back(','); };
  append_field(row_, e.t);
  comma();
  const std::string_view kind = to_string(e.kind);
  row_.append(kind.data(), kind.data() + kind.size());
  fmt::format_to(fmt::appender(row_), FMT_COMPILE(",{},"), e.wall);
  for (double value : {e.q, e.qdot_before, e.qdot_after}) {
    append_field(row_, value);
    comma();
  }
  const EventExtension extension = extender_ ? extender_(e) : EventExtension{};
  // the model's own columns, in EventColumn's order
  const std::array<double, event_column_count> optional = {
      e.normal_impulse, e.tangential_velocity, e.normal_force, e.friction_work,
      extension.instantaneous_residual, extension.sliding_residual, e.tangential_velocity_after};
  for (std::size_t k = 0; k < event_column_count; ++k)
    if (columns_.has(static_cast<EventColumn>(k))) {
      append_field(row_, optional[k]);
      comma();
    }
  append_field(row_, e.accumulation_error);
  row_.push_back('\n');
  out_.write(row_.data(), static_cast<std::streamsize>(row_.size()));
}

TrajectoryCsvWriter::TrajectoryCsvWriter(AtomicFile& file) : out_(file.stream()) {
  out_ << "t,q,qdot,mode\n";
}

void TrajectoryCsvWriter::write(const TrajectorySample& s) {
  row_.clear();
  append_field(row_, s.t);
  row_.push_back(',');
  append_field(row_, s.q);
  row_.push_back(',');
  append_field(row_, s.qdot);
  row_.push_back(',');
  append_csv_text(row_, s.mode);
  row_.push_back('\n');
  out_.write(row_.data(), static_cast<std::streamsize>(row_.size()));
}

void write_events_csv(AtomicFile& file, std::span<const EventRecord> events,
                      EventExtender extender, EventColumns columns) {
  EventsCsvWriter writer(file, std::move(extender), columns);
  for (const auto& e : events) writer.write(e);
}

void write_trajectory_csv(AtomicFile& file, std::span<const TrajectorySample> samples) {
  TrajectoryCsvWriter writer(file);
  for (const auto& s : samples) writer.write(s);
}

void write_json(AtomicFile& file, const nlohmann::json& document) {
  file.stream() << document.dump(2) << '\n';
}

}  // namespace impactlab
