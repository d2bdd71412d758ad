#include "pipeline/outputs/output_point_cache.hpp"

#include <cctype>
#include <cfloat>
#include <cmath>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/mesh_file.hpp"
#include "io/obj.hpp"
#include "io/point_cache.hpp"
#include "core/errors.hpp"
#include "pipeline/outputs/output_staged.hpp"
#include "pipeline/sequence/shard.hpp"
#include "pipeline/sequence/frame_sources.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// A frame's number in the animation: a PC2 input's sample times, else the index.
double frame_number(const FrameSource& source, int index) {
  if (const PointCacheHeader* h = source.point_cache(); h && h->format == PointCacheFormat::Pc2)
    return double(h->start) + double(index) * double(h->sample_rate);
  return double(index);
}

// A header value in float32. A PC2 input's frame numbers are bounded (io/point_cache.hpp), so only
// an MDD time (frame number / output.point_cache.fps) can be beyond float32's range, and only
// for an fps far below any real one.
float header_value(double x, const std::string& what) {
  if (!(std::fabs(x) <= double(FLT_MAX)))
    throw ConfigError("output.point_cache.fps: " + what + " would be " + format_number(x) +
                      ", beyond float32's range: the point cache could not be read back");
  return static_cast<float>(x);
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
    t.start = header_value(frame_number(source, frames.front()), "the start frame");
    if (frames.size() > 1)
      t.sample_rate = header_value(
          frame_number(source, frames[1]) - frame_number(source, frames[0]), "the sample rate");
    else
      t.sample_rate = h && h->format == PointCacheFormat::Pc2 ? h->sample_rate : 1.0f;
    return t;
  }
  for (int i : frames) {
    const std::optional<double> time = source.time(i);
    t.times.push_back(header_value(time ? *time : frame_number(source, i) / options.fps,
                                   "the time of frame " + std::to_string(i)));
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

PointCacheOutput::PointCacheOutput(const OutputContext& context)
    : StagedPositionsOutput(context), format_(*point_cache_format(context.config.output.format)) {}

bool PointCacheOutput::enabled(const SequenceJobOptions& config) {
  return point_cache_format(config.output.format).has_value();
}

const char* PointCacheOutput::help() {
  return "  positions/<frame>.bin, sequence.pc2 (or .mdd), rest.obj\n"
         "                              with \"format\": \"pc2\" or \"mdd\": each frame's "
         "corrected\n"
         "                              positions, then all of them as one point cache and the\n"
         "                              template mesh it applies to (a shard writes positions/ "
         "only)\n";
}

json PointCacheOutput::report() const {
  return {{format_ == PointCacheFormat::Pc2 ? "pc2" : "mdd", point_cache_file_name(format_)},
          {"rest_mesh", "rest.obj"},
          {"positions", "positions/"}};
}

std::vector<std::string> PointCacheOutput::assembled_files() const {
  return {point_cache_file_name(format_).string(), "rest.obj"};
}

std::string PointCacheOutput::describe_assembled(const std::vector<int>& frames) const {
  return "  " + point_cache_file_name(format_).string() + " (" + frames_text(int(frames.size())) +
         " of " + point_cache_format_label(format_) +
         " float32 positions), rest.obj (the template mesh the cache applies to)\n";
}

void PointCacheOutput::assemble(const FinishedFrames& done, const PositionsReader& read) const {
  const std::string rest = format_rest_obj(config_, source());
  const int n = parse_obj(rest, "rest.obj").mesh.num_vertices();
  write_point_cache(config_.output.dir / point_cache_file_name(format_), format_, n,
                    int(done.frames.size()),
                    point_cache_timing(format_, source(), done.frames, config_.output.point_cache),
                    [&](int k) { return read(k, n); });
  write_file_atomic(config_.output.dir / "rest.obj", rest);
}

}  // namespace sm
