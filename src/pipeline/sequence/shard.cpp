#include "pipeline/sequence/shard.hpp"

#include <algorithm>

#include "core/errors.hpp"

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

std::vector<int> shard_frames(const std::vector<int>& selected, const ShardOptions& shard) {
  const auto S = static_cast<long long>(selected.size());
  const long long begin = S * shard.index / shard.count;
  const long long end = S * (shard.index + 1) / shard.count;
  return std::vector<int>(selected.begin() + begin, selected.begin() + end);
}

namespace {

std::string shard_suffix(const ShardOptions& shard) {
  if (!shard.sharded()) return "";
  return ".shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count);
}

}  // namespace

std::string summary_file_name(const ShardOptions& shard) {
  return "summary" + shard_suffix(shard) + ".csv";
}

std::string report_file_name(const ShardOptions& shard) {
  return "report" + shard_suffix(shard) + ".json";
}

std::string iterations_file_name(const ShardOptions& shard) {
  return "iterations" + shard_suffix(shard) + ".csv";
}

std::string shard_label(const ShardOptions& shard) {
  return "shard " + format_shard(shard);
}

ShardOptions parse_shard(std::string_view text, std::string_view what) {
  const std::string name(what);
  const auto bad = [&](const std::string& why) {
    throw ConfigError(name + ": " + why + ", got \"" + std::string(text) + "\"");
  };
  const size_t slash = text.find('/');
  const auto number = [&](std::string_view s) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string_view::npos)
      bad("expected I/N: shard I (0-based) of N, e.g. 0/4");
    return std::stoi(std::string(s));
  };
  if (slash == std::string_view::npos) bad("expected I/N: shard I (0-based) of N, e.g. 0/4");
  ShardOptions shard;
  shard.index = number(text.substr(0, slash));
  shard.count = number(text.substr(slash + 1));
  if (shard.count < 1 || shard.count > 100000) bad("N must be in [1, 100000]");
  if (shard.index >= shard.count)
    bad("I is 0-based and must be below N (like a Slurm array task id or a Kubernetes "
        "JOB_COMPLETION_INDEX)");
  return shard;
}

std::string format_shard(const ShardOptions& shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

}  // namespace sm
