#pragma once
/// A sequence job's per-frame record, records/<frame name>.json: the frame's summary row (every
/// field, exact), the hashes of what made it (config, template, input) and of what it wrote (the
/// path, size and SHA-256 of each output file). It is written last, after the frame's outputs, and
/// removed before they are rewritten, so a record always describes complete files on disk. Resume
/// (which skips frames whose record is current) and merge (which rebuilds summary.csv and
/// report.json from the records of every shard) both rely on it alone.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/sequence/sequence_options.hpp"
#include "pipeline/sequence/sequence_types.hpp"

namespace sm {

/// The value of a record's "format" key.
inline constexpr const char* kFrameRecordFormat = "seqmassage frame record 1";

/// One file a frame wrote, relative to output.dir ("frames/frame_0007.obj").
struct RecordedOutput {
  std::string path;
  uint64_t size = 0;
  std::string sha256;  ///< 64 hex digits, as `sha256sum` prints it
};

struct FrameRecord {
  std::string config_hash;    ///< frame_config_hash of the run's config
  std::string template_hash;  ///< template_hash of the template
  std::string input_hash;     ///< FrameSource::input_hash of the frame
  std::vector<RecordedOutput> outputs;
  FrameSummary summary;        ///< summary.csv's row and the frame's part of report.json
  /// The outputs' rows for finish(), by record key (FrameOutput::kRecordKey): the frame's
  /// iterations.csv rows under "iterations_csv" (output.iterations).
  RecordRows record_rows;
};

/// output_dir/records/<frame name with extension .json>.
std::filesystem::path record_file(const std::filesystem::path& output_dir,
                                  const std::string& frame_name);

/// SHA-256 of everything in `config` that decides a frame's outputs and summary row: the resolved
/// config (to_json) without the keys that do not (threads, frames_in_flight, input.range,
/// output.dir, output.timings, shard, resume), and the program's version_info().
std::string frame_config_hash(const SequenceJobOptions& config);
/// The same with the versions a report names (`seqmassage merge` recomputes a shard's hash from
/// its report's config and versions).
std::string frame_config_hash(const SequenceJobOptions& config, const nlohmann::json& versions);

/// SHA-256 of the template's positions and triangles (exact bytes).
std::string template_hash(const TriMesh& templ);

nlohmann::json to_json(const FrameSummary& summary);
/// Throws InputError naming the missing or wrong key.
FrameSummary frame_summary_from_json(const nlohmann::json& json);

nlohmann::json to_json(const FrameRecord& record);
/// Throws InputError naming the missing or wrong key.
FrameRecord frame_record_from_json(const nlohmann::json& json);

/// The record in `file`; nothing if there is none. A record that cannot be read or parsed is
/// reported through `problem` and gives nothing too.
std::optional<FrameRecord> read_frame_record(const std::filesystem::path& file,
                                             std::string* problem = nullptr);

/// Why `path` (as a record names it) is not a file inside `dir` reached through no symbolic link:
/// absolute, with "..", or a link at one of its parts; "" if it is fine or missing.
std::string confinement_problem(const std::filesystem::path& dir, const std::string& path);

/// "" if every output of `record` is in `output_dir` with its recorded size and, with
/// `check_content`, its SHA-256; else what is wrong with the first one that is not. A recorded
/// path must stay inside `output_dir` (relative, no "..") and name a regular file reached through
/// no symbolic link: a record or a file edited to point elsewhere is refused, never read.
/// `tampered` (if given) is set when the problem is not a missing file but a file that is not
/// what its record says (content, link, path outside).
std::string check_recorded_outputs(const FrameRecord& record,
                                   const std::filesystem::path& output_dir, bool check_content,
                                   bool* tampered = nullptr);

}  // namespace sm
