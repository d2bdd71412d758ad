#include "pipeline/point_cache_output.hpp"

#include <cctype>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "pipeline/frame_sink.hpp"
#include "pipeline/shard.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

// A frame's number in the animation: a PC2 input's sample times, else the index.
double frame_number(const FrameSource& source, int index) {
  if (const PointCacheHeader* h = source.point_cache(); h && h->format == PointCacheFormat::Pc2)
    return double(h->start) + double(index) * double(h->sample_rate);
  return double(index);
}

bool is_obj(const fs::path& file) {
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj";
}

}  // namespace

fs::path point_cache_file_name(PointCacheFormat format) {
  return format == PointCacheFormat::Pc2 ? "sequence.pc2" : "sequence.mdd";
}

PointCacheTiming point_cache_timing(PointCacheFormat format, const FrameSource& source,
                                    const std::vector<int>& frames,
                                    const PointCacheOutputOptions& options) {
  PointCacheTiming t;
  if (format == PointCacheFormat::Pc2) {
    const PointCacheHeader* h = source.point_cache();
    t.start = float(frame_number(source, frames.front()));
    t.sample_rate = frames.size() > 1
                        ? float(frame_number(source, frames[1]) - frame_number(source, frames[0]))
                    : h && h->format == PointCacheFormat::Pc2 ? h->sample_rate
                                                               : 1.0f;
    return t;
  }
  for (int i : frames) {
    const std::optional<double> time = source.time(i);
    t.times.push_back(float(time ? *time : frame_number(source, i) / options.fps));
  }
  return t;
}

std::string format_rest_obj(const SequenceJobOptions& config, const FrameSource& source) {
  if (config.templ.mesh.empty()) {
    const int t = config.templ.frame;
    const SourceFrame frame = source.decode(t, source.fetch(t));
    return frame.bytes.empty() ? format_obj(*frame.obj, frame.mesh.V) : frame.bytes;
  }
  if (is_obj(config.templ.mesh)) return read_file(config.templ.mesh);
  const TriMesh templ = read_mesh(config.templ.mesh);
  const int first = select_frames(config.input.range, source.size()).front();
  return format_obj(*source.decode(first, source.fetch(first)).obj, templ.V);
}

std::vector<std::string> assemble_point_cache(const SequenceJobOptions& config,
                                              const FrameSource& source,
                                              const std::vector<int>& frames) {
  const PointCacheFormat format = *point_cache_format(config.output.format);
  const fs::path cache = config.output.dir / point_cache_file_name(format);
  if (frames.empty())
    return {"no frame was processed, so " + cache.filename().string() + " and rest.obj were not "
            "written"};
  const std::string rest = format_rest_obj(config, source);
  const int n = parse_obj(rest, "rest.obj").mesh.num_vertices();
  int next = 0;
  write_point_cache(cache, format, n, int(frames.size()),
                    point_cache_timing(format, source, frames, config.output.point_cache),
                    [&](int k) {
                      if (k != next++)
                        throw std::logic_error("assemble_point_cache: frames read out of order");
                      return read_frame_positions(config.output.dir, source, frames[size_t(k)], n);
                    });
  write_file_atomic(config.output.dir / "rest.obj", rest);
  return {};
}

}  // namespace sm
