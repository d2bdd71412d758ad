#pragma once
/// Which frames a sequence job runs: the selection (input.range) and, for a sharded run (cluster
/// job arrays), the shard's block of it; and the names of a shard's summary and report, which
/// never collide with another shard's.
#include <string>
#include <vector>

#include "io/config.hpp"

namespace sm {

/// The frames `range` selects among `count`, in order. Throws ConfigError (input.range.start
/// beyond the last frame, or nothing selected).
std::vector<int> select_frames(const FrameRange& range, int count);

/// Shard `shard.index` of `selected` (the job's selected frames, in order): the contiguous block
/// selected[⌊i·S/N⌋ .. ⌊(i+1)·S/N⌋) for S frames and N shards, so block sizes differ by at most one
/// and the blocks, in shard order, are the selection. Empty when N > S for some shards.
std::vector<int> shard_frames(const std::vector<int>& selected, const ShardConfig& shard);

/// "summary.csv", or "summary.shard-I-of-N.csv" for a shard.
std::string summary_file_name(const ShardConfig& shard);

/// "report.json", or "report.shard-I-of-N.json" for a shard.
std::string report_file_name(const ShardConfig& shard);

/// "iterations.csv" (output.iterations), or "iterations.shard-I-of-N.csv" for a shard.
std::string iterations_file_name(const ShardConfig& shard);

/// "shard 1/3" (I is 0-based).
std::string shard_label(const ShardConfig& shard);

}  // namespace sm
