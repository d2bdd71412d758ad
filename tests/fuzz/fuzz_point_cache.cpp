// Fuzz target: the PC2 and MDD readers and writers (io/point_cache.hpp). The first byte chooses
// the format (even: PC2, odd: MDD); the rest is the file.
#include <cmath>
#include <string>
#include <string_view>

#include "fuzz_targets.hpp"
#include "io/point_cache.hpp"
#include "core/coordinate_limit.hpp"
#include "core/errors.hpp"

namespace sm::fuzz {

void fuzz_point_cache(const uint8_t* data, size_t size) {
  if (size == 0) return;
  const PointCacheFormat format = data[0] % 2 ? PointCacheFormat::Mdd : PointCacheFormat::Pc2;
  const std::string_view file(reinterpret_cast<const char*>(data) + 1, size - 1);
  PointCacheHeader header;
  std::vector<Positions> frames;
  try {
    header = parse_point_cache_header(file, file.size(), format, "fuzz");
    expect(header.points >= 1 && header.frames >= 1, "accepted a count below 1");
    expect(header.file_size() == file.size(), "accepted a size the counts do not give");
    for (int k = 0; k < header.frames; ++k)
      frames.push_back(decode_point_cache_frame(
          file.substr(header.data_offset + uint64_t(k) * header.frame_bytes(), header.frame_bytes()),
          header, k, "fuzz"));
  } catch (const InputError&) {
    return;  // rejected with a message: the documented outcome
  }
  for (const Positions& V : frames) {
    expect(V.rows() == header.points && V.allFinite(), "a frame of the wrong size or not finite");
    expect(V.cwiseAbs().maxCoeff() <= kMaxCoordinate, "accepted a coordinate beyond the limit");
  }
  if (format == PointCacheFormat::Mdd)
    expect(header.times.size() == size_t(header.frames), "MDD times and frames differ");

  // Written back with the same timing, an accepted file is the same bytes (float32 values pass
  // through doubles exactly), and the writer's header is one the reader accepts.
  const PointCacheTiming timing{header.start, header.sample_rate, header.times};
  std::string written = format_point_cache_header(format, header.points, header.frames, timing);
  try {
    (void)parse_point_cache_header(written, file.size(), format, "fuzz-written");
    for (int k = 0; k < header.frames; ++k)
      written += format_point_cache_frame(format, frames[size_t(k)], "fuzz-written");
  } catch (const InputError& e) {
    throw FuzzFinding(std::string("an accepted cache does not write back: ") + e.what());
  }
  expect(written == file, "the cache written back differs from the file read");
}

}  // namespace sm::fuzz
