#pragma once
/// `seqmassage merge OUTPUT_DIR`: combines the shards of a sharded sequence job (--shard I/N, each
/// a process writing into the same output folder) into the summary.csv and report.json of one
/// run, and for glTF output assembles sequence.glb from every shard's positions files.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/sequence/shard.hpp"

namespace sm {

/// A shard's report.shard-I-of-N.json, read.
struct ShardReport {
  ShardOptions shard;
  std::string file;  ///< report.shard-I-of-N.json
  nlohmann::json report;
  std::vector<std::pair<int, std::string>> frames;  ///< its "shard.frames": (index, name)
};

/// Every shard report in `dir`, by index. Throws IoError when `dir` is not a folder or a report
/// cannot be read, InputError when there is none, when they are of different splits, or when one
/// is not a shard report (or reached through a link).
std::vector<ShardReport> read_shard_reports(const std::filesystem::path& dir);

/// The job's config as shards must agree on it: without threads, frames_in_flight and the output
/// folder's path (mounted elsewhere on another node).
nlohmann::json job_config(const nlohmann::json& config);

/// The first JSON path at which `a` and `b` differ, with both values ("" if equal).
std::string first_difference(const nlohmann::json& a, const nlohmann::json& b,
                             const std::string& path = "");

/// "frames 5 to 9 (a.obj to e.obj), frame 12": contiguous runs of `frames`, with their names
/// where `names` knows them; at most 20 runs.
std::string describe_frames(const std::vector<int>& frames, const std::map<int, std::string>& names);

struct MergeResult {
  int shards = 0;                     ///< N
  std::vector<FrameSummary> frames;   ///< every selected frame, in order
  int failed = 0;                     ///< frames with status "failed"
  std::vector<std::string> warnings;  ///< report.json's
  std::vector<std::string> written;   ///< files written, relative to the output folder
  std::vector<std::string> notices;   ///< not in report.json: a lock file taken over
};

/// Merges the shards in `output_dir`, holding its lock (lock_output_folder: IoError while a shard
/// or another run writes there): reads every report.shard-I-of-N.json, checks that all N
/// shards are there, complete, and ran the same job (config apart from threads and
/// frames_in_flight, template, program version: their hashes and the reports' config), that
/// their frames are the selection's blocks (none missing, none twice), and that every frame's
/// record (records/<frame>.json) matches and its outputs are there with their recorded sizes.
/// Then writes summary.csv and report.json from the records, byte for byte what one unsharded
/// run of the same config writes (with "output": {"timings": false}; with timings, the times
/// differ), and for "format": "gltf" sequence.glb (which needs the glTF input). Throws
/// InputError listing every missing or inconsistent shard and frame, and how to redo them;
/// IoError when a file cannot be read or written. Shard files are left in place.
MergeResult merge_shards(const std::filesystem::path& output_dir);

}  // namespace sm
