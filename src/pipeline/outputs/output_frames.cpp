#include "pipeline/outputs/output_frames.hpp"

#include <algorithm>
#include <cstring>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_write.hpp"
#include "io/obj.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

fs::path positions_file(const std::string& frame_name) {
  return fs::path("positions") / fs::path(frame_name).replace_extension(".bin");
}

Positions read_positions_file(const fs::path& output_dir, const std::string& frame_name,
                              Eigen::Index n) {
  const fs::path file = output_dir / positions_file(frame_name);
  const std::string bytes = read_file(file);
  if (bytes.size() != size_t(n) * 3 * sizeof(double))
    throw IoError("'" + file.string() + "': " + std::to_string(bytes.size()) +
                  " bytes, but the corrected positions of " + std::to_string(n) +
                  " vertices take " + std::to_string(size_t(n) * 3 * sizeof(double)));
  Positions V(n, 3);
  std::memcpy(V.data(), bytes.data(), bytes.size());
  return V;
}

// ---------------------------------------------------------------------------------------------
// OBJ files.

ObjFramesOutput::ObjFramesOutput(const OutputContext& context)
    : dir_(context.config.output.dir), source_(context.source) {}

bool ObjFramesOutput::enabled(const SequenceJobOptions& config) {
  return config.output.format == OutputFormat::Obj;
}

const char* ObjFramesOutput::help() {
  return "  frames/<input name>.obj     the corrected frames (\"format\": \"obj\", the default)\n";
}

std::vector<fs::path> ObjFramesOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(dir_ / "frames" / source_->name(i));
  return out;
}

std::vector<fs::path> ObjFramesOutput::folders() const {
  return {dir_ / "frames"};
}

std::string ObjFramesOutput::describe(const std::vector<int>& frames) const {
  return "  frames/<name>.obj (" + std::to_string(frames.size()) + " files)\n";
}

json ObjFramesOutput::report() const {
  return {{"frames", "frames/"}};
}

ResultNames ObjFramesOutput::results() const {
  return {{"frames/"}, {}};
}

OutputFrame ObjFramesOutput::encode(const FrameOutcome& f) const {
  OutputFrame out;
  out.files.emplace_back(fs::path("frames") / source_->name(f.index),
                         f.unchanged && !f.input->bytes.empty() ? f.input->bytes
                                                                : format_obj(*f.input->obj, *f.output));
  return out;
}

// ---------------------------------------------------------------------------------------------
// One GLB, assembled at the end from the positions files.

GlbFramesOutput::GlbFramesOutput(const OutputContext& context)
    : config_(context.config),
      source_(context.source),
      gltf_(context.gltf ? context.gltf() : nullptr) {
  if (!gltf_) throw ConfigError("output.format: \"gltf\" needs a glTF input (input.gltf)");
  // Refuses, at planning, what the GLB could not be assembled from (sequence.glb is written last).
  check_gltf_sequence_source(*gltf_, config_.output.gltf);
}

bool GlbFramesOutput::enabled(const SequenceJobOptions& config) {
  return config.output.format == OutputFormat::Gltf;
}

const char* GlbFramesOutput::help() {
  return "  positions/<frame>.bin, sequence.glb\n"
         "                              with \"format\": \"gltf\" (glTF input): each frame's "
         "corrected\n"
         "                              positions, and the corrected animation as one GLB, a "
         "morph\n"
         "                              target per frame (a shard writes positions/ only)\n";
}

std::vector<fs::path> GlbFramesOutput::files(const std::vector<int>& frames) const {
  std::vector<fs::path> out;
  for (int i : frames) out.push_back(config_.output.dir / positions_file(source_->name(i)));
  out.push_back(config_.output.dir / "sequence.glb");
  return out;
}

std::vector<fs::path> GlbFramesOutput::folders() const {
  return {config_.output.dir / "positions"};
}

std::string GlbFramesOutput::describe(const std::vector<int>& frames) const {
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

json GlbFramesOutput::report() const {
  return {{"gltf", "sequence.glb"}, {"positions", "positions/"}};
}

ResultNames GlbFramesOutput::results() const {
  if (config_.shard.sharded()) return {{"positions/"}, {}};  // `seqmassage merge` assembles it
  return {{"positions/", "sequence.glb"}, {}};
}

OutputFrame GlbFramesOutput::encode(const FrameOutcome& f) const {
  const Positions& V = *f.output;
  OutputFrame out;
  out.files.emplace_back(
      positions_file(source_->name(f.index)),
      std::string(reinterpret_cast<const char*>(V.data()), size_t(V.size()) * sizeof(double)));
  return out;
}

OutputFinish GlbFramesOutput::finish(const FinishedFrames& done) const {
  if (config_.shard.sharded()) return {};  // `seqmassage merge` assembles it
  const fs::path glb = config_.output.dir / "sequence.glb";
  if (done.frames.empty())
    return {{"no frame was processed, so " + glb.filename().string() + " was not written"},
            {"sequence.glb"}};
  const GltfSequence& sequence = *gltf_;
  GltfSequence written = sequence;  // the frames done, at their times
  written.times.clear();
  for (int i : done.frames) written.times.push_back(sequence.times[size_t(i)]);
  const Eigen::Index n = sequence.rest.num_vertices();
  int next = 0;
  write_gltf_sequence(
      glb, written,
      [&](int k) {
        if (k != next++) throw std::logic_error("GlbFramesOutput: frames read out of order");
        return read_positions_file(config_.output.dir, done.names[size_t(k)], n);
      },
      config_.output.gltf);
  return {{}, {"sequence.glb"}};
}

}  // namespace sm
