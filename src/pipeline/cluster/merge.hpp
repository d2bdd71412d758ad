#pragma once
/// `seqmassage merge OUTPUT_DIR`: combines the shards of a sharded sequence job (--shard I/N, each
/// a process writing into the same output folder) into the summary.csv and report.json of one
/// run, and for glTF output assembles sequence.glb from every shard's positions files.
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/sequence/frame_summary.hpp"

namespace sm {

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
