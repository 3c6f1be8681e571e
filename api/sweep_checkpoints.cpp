#include <impactlab/api/sweep_checkpoints.hpp>

#include <cstdint>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include <impactlab/io/bad_input.hpp>

namespace impactlab {

std::string sweep_checkpoint_name(int rank) { return fmt::format("checkpoint-{}.jsonl", rank); }

namespace {

constexpr std::string_view checksum_member = ",\"checksum\":\"";

// FNV-1a, 64 bits: a checksum against edits and damage, not an adversary's
// forgery (whoever can write the checkpoint can run the sweep)
std::string checksum(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : text) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return fmt::format("{:016x}", hash);
}

// The record's JSON of a checkpoint line whose checksum matches; nullopt
// for one whose checksum is missing or wrong.
std::optional<std::string> checked_json(std::string_view line) {
  const std::size_t member = line.rfind(checksum_member);
  if (member == std::string_view::npos) return std::nullopt;
  const std::string_view stated = line.substr(member + checksum_member.size());
  std::string json(line.substr(0, member));
  json += '}';
  if (stated != checksum(json) + "\"}") return std::nullopt;
  return json;
}

}  // namespace

std::string sweep_checkpoint_line(const SweepRecord& record) {
  std::string json = to_json_line(record);
  const std::string stated = checksum(json);
  json.pop_back();  // the closing brace, after the last member
  return json + std::string(checksum_member) + stated + "\"}";
}

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
    int line_number = 1;
    for (std::streamoff offset = in.tellg(); std::getline(in, line); offset = in.tellg()) {
      ++line_number;
      // a last line without its line break was cut short by a kill: its
      // point is computed again
      if (in.eof()) break;
      const std::optional<std::string> json = checked_json(line);
      if (!json)
        throw BadInput("checkpoint", fmt::format("{}:{}", entry.path().string(), line_number),
                       "the line's checksum does not match (edited or damaged); delete the "
                       "file to compute its points again");
      auto record = from_json_line(*json);
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
  const std::optional<std::string> json = checked_json(line);
  auto record = json ? from_json_line(*json) : std::nullopt;
  if (!record || record->task != key.first || record->position != key.second)
    throw std::runtime_error(fmt::format("checkpoint {} changed while the sweep read it back",
                                         files_[place->second.file].string()));
  return std::move(*record);
}

}  // namespace impactlab
