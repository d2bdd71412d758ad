#pragma once
/// `seqmassage merge OUTPUT_DIR` for a track job's shards (--shard I/N): checks that every shard
/// ran the same job and completed its block, then writes the whole run's summary.csv,
/// report.json and whole-sequence outputs (sequence.pc2 / .mdd / .glb, report.html) from the
/// shards' reports and per-frame files, and reports the seams.
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/track/track_job.hpp"

namespace sm {

/// A frame where one shard's block begins after another's: tracked from the template
/// registered directly onto it, not from the previous frame's fit.
struct TrackSeam {
  int frame = 0;
  int shard = 0;  ///< the shard whose block it begins
};

struct TrackMergeResult {
  int shards = 0;                     ///< N
  std::vector<TrackRow> frames;       ///< every selected frame, in order
  std::vector<TrackSeam> seams;       ///< in frame order
  int lost = 0, recovered = 0;
  std::vector<std::string> warnings;  ///< report.json's
  std::vector<std::string> written;   ///< files written, relative to the output folder
  std::vector<std::string> notices;   ///< not in report.json: a lock file taken over
};

/// "track" when the shard reports in `dir` are a track job's, else "" (also when there are
/// none or they cannot be read: merge_shards, holding the lock, says why).
std::string shard_job(const std::filesystem::path& dir);

/// Merges the track shards in `dir`, holding its lock: the shards must agree on the program
/// version and the config (apart from threads, shard and output.dir), each must have completed
/// its block of the selection, and every frame's files must be in place (regular files, no
/// links). The job is planned again from the config (its input folder and template must be
/// reachable) to finish the whole-run outputs. Throws InputError listing what is missing or
/// inconsistent and the commands that redo it; IoError when a file cannot be read or written.
/// Shard files are left in place.
TrackMergeResult merge_track_shards(const std::filesystem::path& dir);

}  // namespace sm
