#include "pipeline/outputs/output_frames.hpp"

#include <algorithm>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_write.hpp"
#include "io/obj.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

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
    : StagedPositionsOutput(context), gltf_(context.gltf ? context.gltf() : nullptr) {
  if (!gltf_)  // the config refuses "format": "gltf" without input.gltf (config.cpp, validate)
    throw std::logic_error("GlbFramesOutput: no glTF asset for output.format \"gltf\"");
  // Refuses, at planning, what the GLB could not be assembled from (sequence.glb is written last).
  check_gltf_sequence_source(*gltf_, config_.output.gltf);
}

bool GlbFramesOutput::enabled(const SequenceJobOptions& config) {
  return config.output.format == OutputFormat::Gltf;
}

const char* GlbFramesOutput::help() {
  return "  positions/<frame>.bin, sequence.glb\n"
         "                              with \"format\": \"gltf\" (glTF input, or the track\n"
         "                              job): each frame's corrected positions, and the\n"
         "                              corrected animation as one GLB, a morph target per\n"
         "                              frame (a shard writes positions/ only)\n";
}

json GlbFramesOutput::report() const {
  return {{"gltf", "sequence.glb"}, {"positions", "positions/"}};
}

std::vector<std::string> GlbFramesOutput::assembled_files() const {
  return {"sequence.glb"};
}

std::string GlbFramesOutput::describe_assembled(const std::vector<int>& frames) const {
  const int per_mesh = std::max(1, config_.output.gltf.frames_per_mesh);
  const size_t meshes = (frames.size() + size_t(per_mesh) - 1) / size_t(per_mesh);
  return "  sequence.glb (" + std::to_string(frames.size()) +
         " frames, one morph target each, over " + std::to_string(meshes) + " mesh" +
         (meshes == 1 ? "" : "es") + "; normals " +
         (config_.output.gltf.normals ? "turned with the surface" : "left to the viewer") + ")\n";
}

void GlbFramesOutput::assemble(const FinishedFrames& done, const PositionsReader& read) const {
  const GltfSequence& sequence = *gltf_;
  GltfSequence written = sequence;  // the frames done, at their times
  written.times.clear();
  for (int i : done.frames) written.times.push_back(sequence.times[size_t(i)]);
  const Eigen::Index n = sequence.rest.num_vertices();
  // A sequence built from an OBJ template: the frames are positions of its `v` rows.
  const auto frame = [&](int k) -> Positions {
    if (sequence.rest_source.empty()) return read(k, n);
    const Positions V = read(k, sequence.source_rows);
    Positions rest(n, 3);
    for (Eigen::Index r = 0; r < n; ++r) rest.row(r) = V.row(sequence.rest_source[size_t(r)]);
    return rest;
  };
  write_gltf_sequence(config_.output.dir / "sequence.glb", written, frame, config_.output.gltf);
}

}  // namespace sm
