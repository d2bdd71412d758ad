#pragma once
/// output.html: report.html, a self-contained page of the run (docs/outputs.md): the per-frame
/// figures of summary.csv as plots and a sortable table, the shear histogram, failures, warnings,
/// the resolved config and versions, and a 3D player of the input and output frames side by
/// side. Each frame keeps the player's data in report_data/<frame>.bin (positions and shear, as
/// float32), the run its template in report_data/template.bin, so that --resume and `seqmassage
/// merge` assemble the page without running a frame again. A shard writes the data only: the
/// merge writes the page.
#include <optional>

#include "pipeline/outputs/frame_output.hpp"
#include "pipeline/report/html_sequence.hpp"

namespace sm {

class HtmlReportOutput : public FrameOutput {
 public:
  explicit HtmlReportOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  /// The template's triangles and the checker's texture coordinates (checker.hpp's template_uv).
  void start(const SequencePlan& plan) override;
  OutputFrame encode(const FrameOutcome& frame) const override;
  std::vector<std::pair<std::filesystem::path, std::string>> shared_files() const override;
  /// Writes report.html from `done`'s data and summaries (not for a shard).
  OutputFinish finish(const FinishedFrames& done) const override;

 private:
  SequenceJobOptions config_;
  std::shared_ptr<const FrameSource> source_;
  std::optional<PlayerTemplate> template_;  // from start()
};

}  // namespace sm
