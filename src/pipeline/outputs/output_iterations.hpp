#pragma once
/// output.iterations: iterations.csv (iterations.shard-I-of-N.csv for a shard), the optimizer's
/// course frame by frame (iteration_log.hpp). Each frame's rows are kept in its record, so that
/// --resume and `seqmassage merge` rebuild the table without running a frame again.
#include "pipeline/outputs/frame_output.hpp"

namespace sm {

class IterationsCsvOutput : public FrameOutput {
 public:
  /// A frame record's iterations.csv rows (the record's field of that name).
  static constexpr const char* kRecordKey = "iterations_csv";

  explicit IterationsCsvOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  std::vector<std::string> check(const std::vector<int>& selected) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  /// output.iterations.shear_frames.
  bool wants_shear_per_iteration(int index) const override;
  /// No file: the frame's rows (OutputFrame::record_rows), for an optimized frame logged.
  OutputFrame encode(const FrameOutcome& frame) const override;
  /// Writes the table of `done`'s record rows.
  OutputFinish finish(const FinishedFrames& done) const override;

 private:
  std::filesystem::path dir_;
  IterationLogOptions options_;
  ShardOptions shard_;
  std::shared_ptr<const FrameSource> source_;
  std::string header_;  // of iterations.csv
};

}  // namespace sm
