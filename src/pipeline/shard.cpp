#include "pipeline/shard.hpp"

#include <algorithm>

#include "mesh/errors.hpp"

namespace sm {

std::vector<int> select_frames(const FrameRange& range, int count) {
  if (range.start >= count)
    throw ConfigError("input.range.start: " + std::to_string(range.start) +
                      " is beyond the last frame (the sequence has " + std::to_string(count) +
                      " frames, 0 to " + std::to_string(count - 1) + ")");
  const int stop = range.stop ? std::min(*range.stop, count) : count;
  std::vector<int> selected;
  for (int i = range.start; i < stop; i += range.step) selected.push_back(i);
  if (selected.empty())
    throw ConfigError("input.range: selects no frames (" + format_frame_range(range) + ")");
  return selected;
}

std::vector<int> shard_frames(const std::vector<int>& selected, const ShardConfig& shard) {
  const auto S = static_cast<long long>(selected.size());
  const long long begin = S * shard.index / shard.count;
  const long long end = S * (shard.index + 1) / shard.count;
  return std::vector<int>(selected.begin() + begin, selected.begin() + end);
}

namespace {

std::string shard_suffix(const ShardConfig& shard) {
  if (!shard.sharded()) return "";
  return ".shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
}

}  // namespace

std::string summary_file_name(const ShardConfig& shard) {
  return "summary" + shard_suffix(shard) + ".csv";
}

std::string report_file_name(const ShardConfig& shard) {
  return "report" + shard_suffix(shard) + ".json";
}

std::string iterations_file_name(const ShardConfig& shard) {
  return "iterations" + shard_suffix(shard) + ".csv";
}

std::string shard_label(const ShardConfig& shard) {
  return "shard " + format_shard(shard);
}

}  // namespace sm
