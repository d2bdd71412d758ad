#include "pipeline/frame_sink.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/gltf_write.hpp"
#include "mesh/errors.hpp"
#include "pipeline/point_cache_output.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path positions_file(const std::string& frame_name) {
  return fs::path("positions") / fs::path(frame_name).replace_extension(".bin");
}

Positions read_frame_positions(const fs::path& output_dir, const FrameSource& source, int index,
                               Eigen::Index n) {
  const fs::path file = output_dir / positions_file(source.name(index));
  const std::string bytes = read_file(file);
  if (bytes.size() != size_t(n) * 3 * sizeof(double))
    throw IoError("'" + file.string() + "': " + std::to_string(bytes.size()) +
                  " bytes, but the corrected positions of " + std::to_string(n) +
                  " vertices take " + std::to_string(size_t(n) * 3 * sizeof(double)));
  Positions V(n, 3);
  std::memcpy(V.data(), bytes.data(), bytes.size());
  return V;
}

namespace {

// Remembers the frames that have a file under output.dir, in order.
class FileWriter : public FrameWriter {
 public:
  void keep(int index) override { frames_.push_back(index); }
  std::vector<std::string> finish() override { return {}; }

 protected:
  std::vector<int> frames_;
};

// ---------------------------------------------------------------------------------------------
// OBJ files: frames/<frame name>, written as they come.

class ObjSink : public FrameSink {
 public:
  ObjSink(const fs::path& out, std::shared_ptr<const FrameSource> source)
      : out_(out), source_(std::move(source)) {}

  std::vector<fs::path> files(const std::vector<int>& frames) const override {
    std::vector<fs::path> out;
    for (int i : frames) out.push_back(out_ / output_file(i));
    return out;
  }
  fs::path output_file(int index) const override {
    return fs::path("frames") / source_->name(index);
  }
  std::string describe(const std::vector<int>& frames) const override {
    return "  frames/<name>.obj (" + std::to_string(frames.size()) + " files)\n";
  }
  json report() const override { return {{"frames", "frames/"}}; }
  std::string encode(const SourceFrame& input, const Positions& V, bool unchanged) const override {
    if (unchanged && !input.bytes.empty()) return input.bytes;
    return format_obj(*input.obj, V);
  }
  std::unique_ptr<FrameWriter> start() const override { return std::make_unique<FileWriter>(); }

 private:
  fs::path out_;
  std::shared_ptr<const FrameSource> source_;
};

// ---------------------------------------------------------------------------------------------
// One GLB, assembled at the end from positions/<frame>.bin (exact doubles, 24 bytes per welded
// vertex and frame), read back one at a time by the GLB writer: memory holds the frames in
// flight and the GLB being assembled, never all the frames as well. The positions files stay:
// they are what --resume and `seqmassage merge` rebuild the GLB from.

// A whole-sequence output assembled from the positions files when the run ends: `assemble` is
// assemble_sequence_glb or assemble_point_cache.
class PositionsWriter : public FileWriter {
 public:
  using Assemble = std::vector<std::string> (*)(const SequenceJobOptions&, const FrameSource&,
                                                const std::vector<int>&);
  PositionsWriter(const SequenceJobOptions& config, std::shared_ptr<const FrameSource> source,
                  Assemble assemble)
      : config_(config), source_(std::move(source)), assemble_(assemble) {}

  std::vector<std::string> finish() override {
    if (config_.shard.sharded()) return {};  // `seqmassage merge` assembles it
    return assemble_(config_, *source_, frames_);
  }

 private:
  const SequenceJobOptions& config_;
  std::shared_ptr<const FrameSource> source_;
  Assemble assemble_;
};

class GlbSink : public FrameSink {
 public:
  GlbSink(const SequenceJobOptions& config, std::shared_ptr<const FrameSource> source)
      : config_(config), source_(std::move(source)) {}

  std::vector<fs::path> files(const std::vector<int>& frames) const override {
    std::vector<fs::path> out;
    for (int i : frames) out.push_back(config_.output.dir / output_file(i));
    out.push_back(config_.output.dir / "sequence.glb");
    return out;
  }
  fs::path output_file(int index) const override { return positions_file(source_->name(index)); }
  std::string describe(const std::vector<int>& frames) const override {
    const int per_mesh = std::max(1, config_.output.gltf.frames_per_mesh);
    const size_t meshes = (frames.size() + size_t(per_mesh) - 1) / size_t(per_mesh);
    std::string text = "  positions/<name>.bin (" + std::to_string(frames.size()) +
                       " files: the corrected positions of each frame)\n";
    if (config_.shard.sharded())
      return text + "  sequence.glb: assembled from every shard's positions by seqmassage merge\n";
    return text + "  sequence.glb (" + std::to_string(frames.size()) +
           " frames, one morph target each, over " + std::to_string(meshes) + " mesh" +
           (meshes == 1 ? "" : "es") + "; normals " +
           (config_.output.gltf.normals ? "turned with the surface" : "left to the viewer") + ")\n";
  }
  json report() const override { return {{"gltf", "sequence.glb"}, {"positions", "positions/"}}; }
  std::string encode(const SourceFrame&, const Positions& V, bool) const override {
    return std::string(reinterpret_cast<const char*>(V.data()), size_t(V.size()) * sizeof(double));
  }
  std::unique_ptr<FrameWriter> start() const override {
    return std::make_unique<PositionsWriter>(config_, source_, &assemble_sequence_glb);
  }

 private:
  const SequenceJobOptions config_;
  std::shared_ptr<const FrameSource> source_;
};

// ---------------------------------------------------------------------------------------------
// One PC2 or MDD cache and rest.obj, assembled at the end from positions/<frame>.bin like the GLB
// (the float32 cache is written from the exact doubles, one frame at a time).

class PointCacheSink : public FrameSink {
 public:
  PointCacheSink(const SequenceJobOptions& config, std::shared_ptr<const FrameSource> source)
      : config_(config),
        source_(std::move(source)),
        format_(*point_cache_format(config.output.format)) {}

  std::vector<fs::path> files(const std::vector<int>& frames) const override {
    std::vector<fs::path> out;
    for (int i : frames) out.push_back(config_.output.dir / output_file(i));
    out.push_back(config_.output.dir / point_cache_file_name(format_));
    out.push_back(config_.output.dir / "rest.obj");
    return out;
  }
  fs::path output_file(int index) const override { return positions_file(source_->name(index)); }
  std::string describe(const std::vector<int>& frames) const override {
    const std::string cache = point_cache_file_name(format_).string();
    std::string text = "  positions/<name>.bin (" + std::to_string(frames.size()) +
                       " files: the corrected positions of each frame)\n";
    if (config_.shard.sharded())
      return text + "  " + cache + ", rest.obj: assembled from every shard's positions by " +
             "seqmassage merge\n";
    return text + "  " + cache + " (" + std::to_string(frames.size()) + " frames of " +
           point_cache_format_label(format_) + " float32 positions), rest.obj (the template " +
           "mesh the cache applies to)\n";
  }
  json report() const override {
    return {{format_ == PointCacheFormat::Pc2 ? "pc2" : "mdd",
             point_cache_file_name(format_).string()},
            {"rest_mesh", "rest.obj"},
            {"positions", "positions/"}};
  }
  std::string encode(const SourceFrame&, const Positions& V, bool) const override {
    return std::string(reinterpret_cast<const char*>(V.data()), size_t(V.size()) * sizeof(double));
  }
  std::unique_ptr<FrameWriter> start() const override {
    return std::make_unique<PositionsWriter>(config_, source_, &assemble_point_cache);
  }

 private:
  const SequenceJobOptions config_;
  std::shared_ptr<const FrameSource> source_;
  PointCacheFormat format_;
};

}  // namespace

std::shared_ptr<const FrameSink> make_frame_sink(const SequenceJobOptions& config,
                                                 std::shared_ptr<const FrameSource> source) {
  switch (config.output.format) {
    case OutputFormat::Obj:
      return std::make_shared<ObjSink>(config.output.dir, std::move(source));
    case OutputFormat::Gltf:
      if (!source->gltf())
        throw ConfigError("output.format: \"gltf\" needs a glTF input (input.gltf)");
      return std::make_shared<GlbSink>(config, std::move(source));
    case OutputFormat::Pc2:
    case OutputFormat::Mdd:
      return std::make_shared<PointCacheSink>(config, std::move(source));
  }
  throw std::logic_error("make_frame_sink: unknown output format");
}

std::vector<std::string> assemble_sequence_glb(const SequenceJobOptions& config,
                                               const FrameSource& source,
                                               const std::vector<int>& frames) {
  const fs::path glb = config.output.dir / "sequence.glb";
  if (frames.empty())
    return {"no frame was processed, so " + glb.filename().string() + " was not written"};
  const GltfSequence& sequence = *source.gltf();
  GltfSequence written = sequence;  // the frames done, at their times
  written.times.clear();
  for (int i : frames) written.times.push_back(sequence.times[size_t(i)]);
  const Eigen::Index n = sequence.rest.num_vertices();
  int next = 0;
  write_gltf_sequence(
      glb, written,
      [&](int k) {
        if (k != next++) throw std::logic_error("assemble_sequence_glb: frames read out of order");
        return read_frame_positions(config.output.dir, source, frames[size_t(k)], n);
      },
      config.output.gltf);
  return {};
}

}  // namespace sm
