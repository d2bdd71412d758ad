#include "pipeline/frame_sink.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/gltf_write.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// ---------------------------------------------------------------------------------------------
// OBJ files: frames/<frame name>, written as they come.

class ObjWriter : public FrameWriter {
 public:
  ObjWriter(fs::path dir, std::shared_ptr<const FrameSource> source)
      : dir_(std::move(dir)), source_(std::move(source)) {}
  void write(int index, const std::string& bytes) override {
    write_file_atomic(dir_ / source_->name(index), bytes);
  }
  std::vector<std::string> finish() override { return {}; }

 private:
  fs::path dir_;
  std::shared_ptr<const FrameSource> source_;
};

class ObjSink : public FrameSink {
 public:
  ObjSink(const fs::path& out, std::shared_ptr<const FrameSource> source)
      : dir_(out / "frames"), source_(std::move(source)) {}

  std::vector<fs::path> files(const std::vector<int>& frames) const override {
    std::vector<fs::path> out;
    for (int i : frames) out.push_back(dir_ / source_->name(i));
    return out;
  }
  std::string describe(const std::vector<int>& frames) const override {
    return "  frames/<name>.obj (" + std::to_string(frames.size()) + " files)\n";
  }
  json report() const override { return {{"frames", "frames/"}}; }
  std::string encode(const SourceFrame& input, const Positions& V, bool unchanged) const override {
    if (unchanged && !input.bytes.empty()) return input.bytes;
    return format_obj(*input.obj, V);
  }
  std::unique_ptr<FrameWriter> start() const override {
    return std::make_unique<ObjWriter>(dir_, source_);
  }

 private:
  fs::path dir_;
  std::shared_ptr<const FrameSource> source_;
};

// ---------------------------------------------------------------------------------------------
// One GLB. The corrected frames are appended to a temporary spool file in frame order (exact
// doubles, 24 bytes per welded vertex and frame) and read back one at a time by the GLB writer
// at the end, so that memory holds the frames in flight and the GLB being assembled, never all
// the frames as well.

class GlbWriter : public FrameWriter {
 public:
  GlbWriter(fs::path glb, std::shared_ptr<const FrameSource> source,
            const GltfWriteOptions& options)
      : glb_(std::move(glb)),
        source_(std::move(source)),
        sequence_(*source_->gltf()),
        options_(options) {
    spool_ = glb_;
    spool_ += ".frames." + std::to_string(::getpid()) + std::string(kTempSuffix);
  }
  ~GlbWriter() override {
    std::error_code ec;
    if (out_.is_open()) out_.close();
    fs::remove(spool_, ec);
  }

  void write(int index, const std::string& bytes) override {
    if (!out_.is_open()) {
      std::error_code ec;
      fs::create_directories(spool_.parent_path(), ec);
      out_.open(spool_, std::ios::binary | std::ios::trunc);
      if (!out_) fail("cannot create");
    }
    out_.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out_) fail("cannot write");
    frames_.push_back(index);
  }

  std::vector<std::string> finish() override {
    if (frames_.empty()) {
      return {"no frame was processed, so " + glb_.filename().string() + " was not written"};
    }
    out_.close();
    if (!out_) fail("cannot write");
    GltfSequence written = sequence_;  // the frames done, at their times
    written.times.clear();
    for (int i : frames_) written.times.push_back(sequence_.times[size_t(i)]);
    std::ifstream in(spool_, std::ios::binary);
    if (!in) fail("cannot open");
    const Eigen::Index n = sequence_.rest.num_vertices();
    int next = 0;
    write_gltf_sequence(
        glb_, written,
        [&](int k) {
          if (k != next++) throw std::logic_error("GlbWriter: frames read out of order");
          Positions V(n, 3);
          in.read(reinterpret_cast<char*>(V.data()), std::streamsize(V.size() * sizeof(double)));
          if (!in) fail("cannot read back");
          return V;
        },
        options_);
    return {};
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw IoError(what + " the temporary frame file '" + spool_.string() +
                  "': " + std::strerror(errno ? errno : EIO));
  }

  fs::path glb_, spool_;
  std::shared_ptr<const FrameSource> source_;  // keeps sequence_ alive
  const GltfSequence& sequence_;
  GltfWriteOptions options_;
  std::ofstream out_;
  std::vector<int> frames_;
};

class GlbSink : public FrameSink {
 public:
  GlbSink(const fs::path& out, std::shared_ptr<const FrameSource> source,
          const GltfWriteOptions& options)
      : glb_(out / "sequence.glb"), source_(std::move(source)), options_(options) {}

  std::vector<fs::path> files(const std::vector<int>&) const override { return {glb_}; }
  std::string describe(const std::vector<int>& frames) const override {
    const int per_mesh = std::max(1, options_.frames_per_mesh);
    const size_t meshes = (frames.size() + size_t(per_mesh) - 1) / size_t(per_mesh);
    return "  sequence.glb (" + std::to_string(frames.size()) +
           " frames, one morph target each, over " + std::to_string(meshes) + " mesh" +
           (meshes == 1 ? "" : "es") + "; normals " +
           (options_.normals ? "turned with the surface" : "left to the viewer") + ")\n";
  }
  json report() const override { return {{"gltf", glb_.filename().string()}}; }
  std::string encode(const SourceFrame&, const Positions& V, bool) const override {
    return std::string(reinterpret_cast<const char*>(V.data()), size_t(V.size()) * sizeof(double));
  }
  std::unique_ptr<FrameWriter> start() const override {
    return std::make_unique<GlbWriter>(glb_, source_, options_);
  }

 private:
  fs::path glb_;
  std::shared_ptr<const FrameSource> source_;
  GltfWriteOptions options_;
};

}  // namespace

std::shared_ptr<const FrameSink> make_frame_sink(const JobConfig& config,
                                                 std::shared_ptr<const FrameSource> source) {
  switch (config.output.format) {
    case OutputFormat::Obj:
      return std::make_shared<ObjSink>(config.output.dir, std::move(source));
    case OutputFormat::Gltf:
      if (!source->gltf())
        throw ConfigError("output.format: \"gltf\" needs a glTF input (input.gltf)");
      return std::make_shared<GlbSink>(config.output.dir, std::move(source), config.output.gltf);
  }
  throw std::logic_error("make_frame_sink: unknown output format");
}

}  // namespace sm
