#pragma once
/// Which frames a sequence job runs: the selection (input.range) and, for a sharded run (cluster
/// job arrays), the shard's block of it; and the names of a shard's summary and report, which
/// never collide with another shard's.
#include <string>
#include <string_view>
#include <vector>

#include "core/frame_selection.hpp"
#include "core/options_table.hpp"

namespace sm {

/// "shard": the part of the selected frames this process runs, for job arrays on a cluster: the
/// selected frames are cut into `count` contiguous blocks of (nearly) equal size, and shard `index`
/// runs block `index`. Its summary and report are named by shard (summary.shard-I-of-N.csv,
/// report.shard-I-of-N.json); `seqmassage merge` combines the shards.
struct ShardOptions {
  int index = 0;  ///< 0-based, < count (a Slurm array task id, a Kubernetes completion index)
  int count = 1;  ///< 1 = not sharded
  bool sharded() const { return count > 1; }
};

/// "count" comes first: "index" is checked against it.
template <>
inline const Fields<ShardOptions>& fields_of<ShardOptions>() {
  using O = ShardOptions;
  static const Fields<O> fields = {
      field<&O::count>("count", closed(1, 100000),
                       "number of shards: the selected frames are cut into `count` contiguous "
                       "blocks of (nearly) equal size; 1 = not sharded"),
      field<&O::index>("index", below_key("count"),
                       "this shard, 0-based (a Slurm array task id, a Kubernetes completion "
                       "index)"),
  };
  return fields;
}

/// Parses "I/N" (0 <= I < N) into a shard. Throws ConfigError naming `what` (e.g. "--shard").
ShardOptions parse_shard(std::string_view text, std::string_view what);

/// "I/N".
std::string format_shard(const ShardOptions& shard);

/// The frames `range` selects among `count`, in order. Throws ConfigError (input.range.start
/// beyond the last frame, or nothing selected).
std::vector<int> select_frames(const FrameRange& range, int count);

/// Shard `shard.index` of `selected` (the job's selected frames, in order): the contiguous block
/// selected[⌊i·S/N⌋ .. ⌊(i+1)·S/N⌋) for S frames and N shards, so block sizes differ by at most one
/// and the blocks, in shard order, are the selection. Empty when N > S for some shards.
std::vector<int> shard_frames(const std::vector<int>& selected, const ShardOptions& shard);

/// "summary.csv", or "summary.shard-I-of-N.csv" for a shard.
std::string summary_file_name(const ShardOptions& shard);

/// "report.json", or "report.shard-I-of-N.json" for a shard.
std::string report_file_name(const ShardOptions& shard);

/// "iterations.csv" (output.iterations), or "iterations.shard-I-of-N.csv" for a shard.
std::string iterations_file_name(const ShardOptions& shard);

/// "shard 1/3" (I is 0-based).
std::string shard_label(const ShardOptions& shard);

}  // namespace sm
