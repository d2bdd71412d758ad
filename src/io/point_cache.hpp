#pragma once
/// Point caches: the vertex positions of every frame of an animated mesh, without connectivity,
/// in the two formats Blender's Mesh Cache modifier, 3ds Max, Maya and Houdini exchange.
///
/// PC2 (little-endian): char[12] "POINTCACHE2\0", int32 version (1), int32 point count, float32
/// start frame, float32 sample rate (frames between samples), int32 sample count, then float32
/// x, y, z per point per sample.
/// MDD (big-endian): int32 frame count, int32 point count, float32 frame times (seconds) [frame
/// count], then float32 x, y, z per point per frame.
///
/// A header is checked against the file's size before anything is allocated, so a hostile header
/// costs nothing; frames are read one at a time by offset.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/enum_names.hpp"
#include "mesh/mesh.hpp"

namespace sm {

enum class PointCacheFormat { Pc2, Mdd };
inline constexpr EnumName<PointCacheFormat> kPointCacheFormatNames[] = {
    {"pc2", PointCacheFormat::Pc2}, {"mdd", PointCacheFormat::Mdd}};

/// "PC2" or "MDD".
const char* point_cache_format_label(PointCacheFormat format);

/// A point cache's header, checked.
struct PointCacheHeader {
  PointCacheFormat format = PointCacheFormat::Pc2;
  int points = 0;            ///< vertices per frame, >= 1
  int frames = 0;            ///< samples (PC2) or frames (MDD), >= 1
  float start = 0.0f;        ///< PC2: the frame of the first sample
  float sample_rate = 1.0f;  ///< PC2: frames from one sample to the next
  std::vector<float> times;  ///< MDD: each frame's time in seconds (finite); empty for PC2
  uint64_t data_offset = 0;  ///< bytes before the first frame's positions

  /// Bytes of one frame's positions: points × 3 × 4.
  uint64_t frame_bytes() const { return uint64_t(points) * 12; }
  /// The file's exact size: data_offset + frames × frame_bytes().
  uint64_t file_size() const { return data_offset + uint64_t(frames) * frame_bytes(); }
};

/// The header of the cache held by `data`, whose first bytes are `data` and whose whole size is
/// `file_size` (data may hold the header only). `name` prefixes messages. Throws InputError for a
/// wrong magic or version (PC2), a count that is not >= 1, a size that is not the one the counts
/// give (truncated, or trailing bytes), a non-finite MDD frame time (naming the frame), and a PC2
/// timing that pc2_timing_problem (io/point_cache_timing.hpp) refuses: a sample rate not above 0,
/// a frame number start + k × rate beyond 1e18 in magnitude.
PointCacheHeader parse_point_cache_header(std::string_view data, uint64_t file_size,
                                          PointCacheFormat format, const std::string& name);

/// Opens `file` (a regular file, or a link to one), reads its header and checks it against the
/// file's size. Throws IoError if it cannot be opened or read, InputError as above (also for a
/// folder, device or pipe).
PointCacheHeader read_point_cache_header(const std::filesystem::path& file,
                                         PointCacheFormat format);

/// The raw bytes of frame `frame` (0-based, below header.frames), read at its offset. Thread-safe
/// (each call opens the file). Throws IoError if the file cannot be read (or got shorter).
std::string read_point_cache_frame_bytes(const std::filesystem::path& file,
                                         const PointCacheHeader& header, int frame);

/// The n×3 positions of frame `frame` from its raw bytes (header.frame_bytes() of them). Throws
/// InputError "<name>: frame F, vertex V: non-finite position (x, y, z)" for NaN or infinity,
/// and "<name>: frame F, vertex V: coordinate y 1e+30 is too large (more than 1e18 ...)" beyond
/// kMaxCoordinate (core/coordinate_limit.hpp), as every mesh reader.
Positions decode_point_cache_frame(std::string_view bytes, const PointCacheHeader& header,
                                   int frame, const std::string& name);

/// What a written cache's header says besides its counts.
struct PointCacheTiming {
  float start = 0.0f;        ///< PC2
  float sample_rate = 1.0f;  ///< PC2
  std::vector<float> times;  ///< MDD: one per frame
};

/// The header bytes of a cache of `frames` frames of `points` points.
std::string format_point_cache_header(PointCacheFormat format, int points, int frames,
                                      const PointCacheTiming& timing);

/// One frame's positions as the format stores them (float32, rounded to nearest). Throws
/// InputError "<what>, vertex V: position (x, y, z) is not finite in float32" for a coordinate
/// that is not finite or beyond float32's range.
std::string format_point_cache_frame(PointCacheFormat format, const Positions& V,
                                     const std::string& what);

/// Writes `path` atomically: the header, then frame(0), frame(1), ... frame(frames − 1), each
/// (points × 3, checked) encoded and written before the next is asked for, so that memory holds
/// one frame. Throws IoError if the file cannot be written, InputError for a timing the reader
/// would refuse (before anything is written), a frame of the wrong size or not finite in float32,
/// and whatever `frame` throws (the destination is then untouched).
void write_point_cache(const std::filesystem::path& path, PointCacheFormat format, int points,
                       int frames, const PointCacheTiming& timing,
                       const std::function<Positions(int)>& frame);

}  // namespace sm
