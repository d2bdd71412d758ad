#pragma once
/// The sequence job's per-frame outputs, one interface and one registry: the corrected frames
/// (OBJ files, or the positions a GLB is assembled from), the per-triangle distortion CSV, the
/// coloured shear PLY meshes, the checker-textured OBJ and the optimizer's iterations.csv. Every
/// place that names the outputs loops over the registry: the plan (which outputs the config
/// enables), the overwrite check, the dry run, the frame records, report.json, the command line's
/// results line and the outputs part of `seqmassage --help`, the clean-up of stale temporaries,
/// and `seqmassage merge`.
///
/// How a frame's output flows: the pipeline's parallel stage hands every output the processed
/// frame (FrameOutcome) and gets back its files (OutputFrame, bytes relative to output.dir); the
/// job writes them atomically, adds them to the frame's record (path, size, SHA-256), and removes
/// them instead when the frame has no output (failed, output.on_failure "skip"). Files that many
/// frames share (the checker texture) are written once, in frame order, before the first frame
/// that asks for them. When the run ends (or stops), finish() completes the whole-run files from
/// the frames that have their files in place (written or kept by --resume); `seqmassage merge`
/// calls the same finish() with every shard's frames.
///
/// Adding an output (for example a point cache of the whole sequence):
///   1. one class deriving from FrameOutput, in its own source file, with a constructor from
///      OutputContext and two static members: `static bool enabled(const SequenceJobOptions&)`
///      (the config asks for it) and `static const char* help()` (its lines of `--help`);
///   2. one line in the registry (frame_outputs.cpp): `output<MyOutput>(),`.
/// An output of one CSV per frame in a folder of its own derives from FrameCsvOutput
/// (output_frame_csv.hpp) and writes only its table.
/// Its options go in OutputOptions (sequence_options.hpp) with their field-table lines.
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "geometry/shear.hpp"
#include "massage/massage.hpp"
#include "pipeline/sequence/frame_source.hpp"
#include "pipeline/sequence/frame_summary.hpp"
#include "pipeline/sequence/sequence_options.hpp"
#include "pipeline/sequence/sequence_types.hpp"

namespace sm {

/// A processed frame, as the outputs see it (valid during the call).
struct FrameOutcome {
  int index = 0;
  const SourceFrame* input = nullptr;             ///< the frame as read
  const Positions* output = nullptr;              ///< its output positions (n×3)
  bool unchanged = false;                         ///< `output` is the input's (template, failed)
  const Eigen::VectorXd* shear_before = nullptr;  ///< eq. 8 of the input frame (m values)
  const Eigen::VectorXd* shear_after = nullptr;   ///< eq. 8 of the output frame
  const MassageResult* result = nullptr;          ///< the optimizer's run; null if not optimized
  /// The shear after every iteration of `result` (shear_observer), for the frames an output
  /// asked it for (FrameOutput::wants_shear_per_iteration); else null or empty.
  const std::vector<std::optional<DistortionSummary>>* shear_per_iteration = nullptr;
};

/// Appends `more`'s rows after `rows`', key by key.
void append_record_rows(RecordRows& rows, const RecordRows& more);

/// One output's part of a frame, encoded.
struct OutputFrame {
  /// The frame's files, relative to output.dir, with their bytes.
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  /// Text the frame's record keeps for finish() under the output's kRecordKey (iterations.csv
  /// rows), so that a frame kept by --resume or merged from a shard contributes without being
  /// processed again.
  std::string record_rows;
  /// The frame's files need the output's shared_files() in place (written once per run).
  bool needs_shared = false;
};

/// The frames of a run (or of every shard, for merge) that finish() completes an output from.
struct FinishedFrames {
  std::vector<int> frames;         ///< the frames whose files are in place, in order
  std::vector<std::string> names;  ///< their names (FrameSource::name), in the same order
  /// Every frame's OutputFrame::record_rows (with files in place or not), in frame order.
  RecordRows record_rows;
  /// Every frame of the run (or of every shard), in order: summary.csv's rows (report.html).
  const std::vector<FrameSummary>* summaries = nullptr;
  /// The run's warnings so far (the plan's, the frames', the outputs' finished before).
  const std::vector<std::string>* warnings = nullptr;
};

/// What finish() did.
struct OutputFinish {
  std::vector<std::string> warnings;
  std::vector<std::string> written;  ///< whole-run files written, relative to output.dir
};

/// The names the command line's results line lists ("results: out/ (frames/, ...)"): those that
/// come before records/ (the frames' folders) and after it (whole-run tables).
struct ResultNames {
  std::vector<std::string> before_records;
  std::vector<std::string> after_records;
};

/// What an output is built from.
struct OutputContext {
  const SequenceJobOptions& config;           ///< output.dir, output.*, shard
  /// The frames' names for the plan's methods; null for `seqmassage merge`, which calls
  /// finish() only (FinishedFrames names the frames).
  std::shared_ptr<const FrameSource> source;
  /// The glTF asset (glTF input), else null: loaded on demand, for the outputs that rebuild it.
  std::function<std::shared_ptr<const GltfSequence>()> gltf;
};

class FrameOutput {
 public:
  virtual ~FrameOutput() = default;

  /// The key under which a frame's record keeps the output's OutputFrame::record_rows; null for
  /// an output that keeps none. A derived output with rows declares its own.
  static constexpr const char* kRecordKey = nullptr;
  /// This output's kRecordKey (set by make_frame_outputs).
  const char* record_key() const { return record_key_; }
  /// Adds `part`'s rows to `rows` under this output's key.
  void add_record_rows(RecordRows& rows, const OutputFrame& part) const;

  // --- The plan (const, no file is touched).
  /// The files a run of `frames` writes, under output.dir (for the overwrite check).
  virtual std::vector<std::filesystem::path> files(const std::vector<int>& frames) const = 0;
  /// The folders it writes into, under output.dir (stale temporaries are removed from them).
  virtual std::vector<std::filesystem::path> folders() const = 0;
  /// The dry run's lines, each "  <file>: <what>\n".
  virtual std::string describe(const std::vector<int>& frames) const = 0;
  /// Warnings of the plan about the `selected` frames (e.g. listed frames the run skips).
  virtual std::vector<std::string> check(const std::vector<int>& /*selected*/) const {
    return {};
  }
  /// report.json "outputs" entries (names relative to output.dir).
  virtual nlohmann::json report() const = 0;
  /// Its names in the results line.
  virtual ResultNames results() const = 0;

  // --- The run.
  /// Called once when a run starts, after the source is prepared, before any frame (e.g. reads
  /// the template's texture coordinates).
  virtual void start(const SequencePlan& /*plan*/) {}
  /// Whether frame `index`'s run measures the shear after every iteration for this output.
  virtual bool wants_shear_per_iteration(int /*index*/) const { return false; }
  /// The output's files of one frame. Thread-safe (called from the parallel stage).
  virtual OutputFrame encode(const FrameOutcome& frame) const = 0;
  /// Files shared by the frames (relative to output.dir), written once per run before the first
  /// frame whose OutputFrame::needs_shared is set.
  virtual std::vector<std::pair<std::filesystem::path, std::string>> shared_files() const {
    return {};
  }
  /// Completes the whole-run files from `done` (nothing for an output of per-frame files only).
  /// Throws IoError when a file cannot be read or written.
  virtual OutputFinish finish(const FinishedFrames& /*done*/) const { return {}; }

 private:
  friend std::vector<std::shared_ptr<FrameOutput>> make_frame_outputs(const OutputContext&);
  const char* record_key_ = nullptr;
};

// --- Helpers for the outputs' plan text.

/// "1 frame", "3 frames".
std::string frames_text(int n);
/// How many of `frames` `selection` contains.
int count_in(const FrameSelection& selection, const std::vector<int>& frames);
/// A warning when `selection` lists frames that are not among `selected` ("key: frames 7, 9 not
/// processed by this run (see input.range and --frames)"), else nothing.
std::vector<std::string> unlisted_frames(const FrameSelection& selection,
                                         const std::vector<int>& selected, const std::string& key);

/// One line of the registry: how to build an output the config enables, and its help.
struct OutputEntry {
  bool (*enabled)(const SequenceJobOptions& config);
  std::shared_ptr<FrameOutput> (*make)(const OutputContext& context);
  const char* (*help)();
  const char* record_key;  ///< FrameOutput::kRecordKey of the output, or null
};

/// The registry line of output class T (see the header's doc).
template <class T>
OutputEntry output() {
  return {&T::enabled, [](const OutputContext& c) -> std::shared_ptr<FrameOutput> {
            return std::make_shared<T>(c);
          },
          &T::help, T::kRecordKey};
}

/// Every output, in the order of the dry run, the records, --help and the results line.
const std::vector<OutputEntry>& output_registry();

/// The outputs `context.config` enables, in registry order. Throws ConfigError for an output
/// the input cannot feed (e.g. "format": "gltf" without a glTF input).
std::vector<std::shared_ptr<FrameOutput>> make_frame_outputs(const OutputContext& context);

/// The record keys of every registered output that keeps rows, in registry order: a frame
/// record holds each (empty where the output is off), so that records compare across configs.
std::vector<std::string> record_row_keys();

/// The outputs part of `seqmassage --help`: every registered output's lines, in order.
std::string outputs_help();

/// The results line's names of `outputs`: their folders, then `middle` (the sequence job's
/// records/), then their whole-run files.
std::vector<std::string> result_names(const std::vector<std::shared_ptr<FrameOutput>>& outputs,
                                      const std::vector<std::string>& middle);

}  // namespace sm
