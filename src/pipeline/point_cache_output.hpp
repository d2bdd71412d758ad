#pragma once
/// A sequence job's point cache output ("output.format": "pc2" or "mdd"): sequence.pc2 /
/// sequence.mdd, every frame's corrected positions as float32, assembled from the frames'
/// positions files (positions/<frame>.bin, as for sequence.glb) when the run ends or when
/// `seqmassage merge` joins the shards; and rest.obj, the template mesh the cache applies to.
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/frame_source.hpp"
#include "pipeline/sequence_options.hpp"

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
/// materials, groups). A template frame: that frame's output when written unchanged (an OBJ
/// frame's bytes). A template mesh: an OBJ file's bytes, else its positions in the OBJ statements
/// of the first selected frame. Reads what it needs from the input (so merge gives the same bytes).
std::string format_rest_obj(const SequenceJobOptions& config, const FrameSource& source);

/// Writes output.dir/sequence.pc2 (or .mdd) of the frames `frames` (in order) from their
/// positions files, one frame in memory at a time, then output.dir/rest.obj, each atomically.
/// Returns warnings (that no frame was given, so nothing was written). Throws IoError when a
/// positions file is missing or has the wrong size or a file cannot be written, InputError for a
/// position beyond float32's range.
std::vector<std::string> assemble_point_cache(const SequenceJobOptions& config,
                                              const FrameSource& source,
                                              const std::vector<int>& frames);

}  // namespace sm
