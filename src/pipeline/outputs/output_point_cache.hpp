#pragma once
/// The point cache output ("output.format": "pc2" or "mdd"): sequence.pc2 / sequence.mdd, every
/// frame's corrected positions as float32, assembled when the run ends (or by `seqmassage merge`)
/// from the frames' positions files, as sequence.glb is; and rest.obj, the template mesh the
/// cache applies to.
#include <memory>
#include <mutex>

#include "pipeline/outputs/output_staged.hpp"

namespace sm {

/// "sequence.pc2" or "sequence.mdd", relative to output.dir.
std::filesystem::path point_cache_file_name(PointCacheFormat format);

/// The header values of a cache of frames `frames` (in order, at least one) of `source`. A frame's
/// number is its index, or for a PC2 input its start + index × sample rate. PC2: start = the first
/// frame's number, sample rate = the step from the first to the second (for one frame: the
/// input's sample rate, or 1). MDD: each frame's time, the source's (glTF, MDD) or its number /
/// `options.fps`.
PointCacheTiming point_cache_timing(PointCacheFormat format, const FrameSource& source,
                                    const std::vector<int>& frames,
                                    const PointCacheOutputOptions& options);

/// The text of rest.obj: the template, with the input's OBJ statements (texture coordinates,
/// materials, groups). A template frame: that frame as an OBJ output writes it unchanged (an OBJ
/// frame's bytes). A template mesh: an OBJ file's bytes, else its positions in the OBJ statements
/// of the first selected frame. Reads what it needs from the input, so merge gives the same bytes.
std::string format_rest_obj(const SequenceJobOptions& config, const FrameSource& source);

/// The frames' positions staged (StagedPositionsOutput); finish() writes output.dir/sequence.pc2
/// (or .mdd) of the done frames, in order, one frame in memory at a time, then rest.obj, each
/// atomically. Throws InputError from finish() for a position beyond float32's range.
class PointCacheOutput : public StagedPositionsOutput {
 public:
  explicit PointCacheOutput(const OutputContext& context);
  static bool enabled(const SequenceJobOptions& config);
  static const char* help();

  nlohmann::json report() const override;

 private:
  std::vector<std::string> assembled_files() const override;
  std::string describe_assembled(const std::vector<int>& frames) const override;
  void assemble(const FinishedFrames& done, const PositionsReader& read) const override;

  PointCacheFormat format_;
};

}  // namespace sm
