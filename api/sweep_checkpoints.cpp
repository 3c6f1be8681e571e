#include <impactlab/api/sweep_checkpoints.hpp>

#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace impactlab {

std::string sweep_checkpoint_name(int rank) { return fmt::format("checkpoint-{}.jsonl", rank); }

SweepCheckpoints::SweepCheckpoints(const std::filesystem::path& directory,
                                   const std::string& header, bool keep_points) {
  if (!std::filesystem::is_directory(directory)) return;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with("checkpoint-") || !name.ends_with(".jsonl")) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::string line;
    if (!std::getline(in, line) || line != header) continue;
    const std::size_t file = files_.size();
    files_.push_back(entry.path());
    for (std::streamoff offset = in.tellg(); std::getline(in, line); offset = in.tellg()) {
      auto record = from_json_line(line);
      if (!record) continue;
      const SweepRecordKey key{record->task, record->position};
      if (records_.contains(key)) continue;  // the first complete line of a point wins
      if (!keep_points) drop_points(*record);
      places_.emplace(key, Place{file, static_cast<std::uint64_t>(offset)});
      records_.emplace(key, std::move(*record));
    }
  }
}

SweepRecord SweepCheckpoints::load(const SweepRecordKey& key) const {
  const auto place = places_.find(key);
  if (place == places_.end())
    throw std::runtime_error(fmt::format("sweep point (task {}, position {}) is in no checkpoint",
                                         key.first, key.second));
  std::ifstream in(files_[place->second.file], std::ios::binary);
  in.seekg(static_cast<std::streamoff>(place->second.offset));
  std::string line;
  std::getline(in, line);
  auto record = from_json_line(line);
  if (!record || record->task != key.first || record->position != key.second)
    throw std::runtime_error(fmt::format("checkpoint {} changed while the sweep read it back",
                                         files_[place->second.file].string()));
  return std::move(*record);
}

}  // namespace impactlab
