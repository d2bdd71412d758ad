#pragma once
/// The outputs that write one CSV per frame into a folder of their own, `<folder>/<frame>.csv`
/// (distortion/, displacement/): the plan's part (files, folder, dry run, report, results line)
/// once, so such an output is its table and nothing else.
#include <string>

#include "pipeline/outputs/frame_output.hpp"

namespace sm {

class FrameCsvOutput : public FrameOutput {
 public:
  /// Files `<output.dir>/<folder>/<frame name>.csv`; report.json names them `"<folder>":
  /// "<folder>/"`.
  FrameCsvOutput(const OutputContext& context, std::string folder);

  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const override;
  std::vector<std::filesystem::path> folders() const override;
  std::string describe(const std::vector<int>& frames) const override;
  nlohmann::json report() const override;
  ResultNames results() const override;
  OutputFrame encode(const FrameOutcome& frame) const override;

 protected:
  /// The frame's table. Thread-safe.
  virtual std::string table(const FrameOutcome& frame) const = 0;

 private:
  std::filesystem::path file(int index) const;  // relative to output.dir

  std::filesystem::path dir_;
  std::string folder_;
  std::shared_ptr<const FrameSource> source_;
};

}  // namespace sm
