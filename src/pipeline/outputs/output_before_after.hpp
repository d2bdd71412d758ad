#pragma once
/// Outputs that show selected frames twice, as read and as corrected:
/// <folder>/before/<frame>.<ext> and <folder>/after/<frame>.<ext>, for the frames of
/// output.<folder>.frames (the coloured shear PLY meshes, the checker-textured OBJ frames).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pipeline/outputs/frame_output.hpp"

namespace sm {

/// The base of the before/after outputs: it owns the two folders, the file names, the frame
/// selection and its plan warning; a derived output encodes a frame's two files.
class BeforeAfterOutput : public FrameOutput {
 public:
  std::vector<std::filesystem::path> files(const std::vector<int>& frames) const final;
  std::vector<std::filesystem::path> folders() const final;
  std::vector<std::string> check(const std::vector<int>& selected) const final;
  OutputFrame encode(const FrameOutcome& frame) const final;

 protected:
  /// `folder`: the output's folder under output.dir and its key under "output" (the frames are
  /// output.<folder>.frames); `extension`: of its files (".ply").
  BeforeAfterOutput(const OutputContext& context, std::string folder, std::string extension,
                    const FrameSelection& frames);

  /// The frame's two files, before and after; nothing for a frame it cannot show yet.
  virtual std::optional<std::pair<std::string, std::string>> encode_sides(
      const FrameOutcome& frame) const = 0;
  /// Files each side folder holds once (after the frames, in files()), from shared_files().
  virtual std::vector<std::string> side_files() const { return {}; }

  /// "<folder>/{before,after}/" as report.json names them.
  nlohmann::json folders_report() const;

  std::filesystem::path dir_;
  std::string folder_;
  std::string extension_;
  FrameSelection frames_;
  std::shared_ptr<const FrameSource> source_;
};

}  // namespace sm
