#include "pipeline/sequence/frame_sources.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <mutex>

#include "core/coordinate_limit.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/frame_folder.hpp"
#include "io/gltf/gltf_obj.hpp"
#include "io/gltf/gltf_scene.hpp"
#include "io/sha256.hpp"
#include "pipeline/sequence/input_kinds.hpp"
#include "pipeline/sequence/point_cache_source.hpp"
#include "pipeline/sequence/synthetic.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// ---------------------------------------------------------------------------------------------
// A folder of OBJ files, one per frame, in natural order.

class ObjFolderSource : public FrameSource {
 public:
  explicit ObjFolderSource(const fs::path& dir) : dir_(dir), files_(list_frames(dir, ".obj")) {}

  int size() const override { return int(files_.size()); }
  std::string name(int i) const override { return files_[size_t(i)].filename().string(); }
  std::string describe() const override {
    return std::to_string(size()) + " OBJ frames in " + dir_.string();
  }
  json report() const override {
    return {{"kind", "obj"}, {"folder", dir_.string()}, {"frames", size()}};
  }
  std::vector<fs::path> files(const std::vector<int>& frames) const override {
    std::vector<fs::path> out;
    for (int i : frames) out.push_back(files_[size_t(i)]);
    return out;
  }
  TriMesh template_frame(int i) const override { return read_obj(files_[size_t(i)]).mesh; }
  std::string fetch(int i) const override { return read_file(files_[size_t(i)]); }
  SourceFrame decode(int i, std::string bytes) const override {
    auto file = std::make_shared<ObjFile>(parse_obj(bytes, files_[size_t(i)].string()));
    SourceFrame frame;
    frame.mesh = file->mesh;
    frame.obj = std::move(file);
    frame.bytes = std::move(bytes);
    return frame;
  }

 protected:
  ObjFolderSource(fs::path dir, std::vector<fs::path> files)
      : dir_(std::move(dir)), files_(std::move(files)) {}

  fs::path dir_;
  std::vector<fs::path> files_;
};

// ---------------------------------------------------------------------------------------------
// The synthetic bending tube or rolled sheet: generated into <output.dir>/input when the run starts (its clean
// frames into <output.dir>/ground_truth), then read like a folder.

class SyntheticSource : public ObjFolderSource {
 public:
  SyntheticSource(const SyntheticOptions& config, const fs::path& output_dir)
      : ObjFolderSource(output_dir / "input", {}),
        sequence_(make_synthetic_sequence(config)),
        ground_truth_dir_(output_dir / "ground_truth") {
    for (int t = 0; t < config.frames; ++t)
      files_.push_back(dir_ / synthetic_frame_name(sequence_, t));
  }

  std::string describe() const override {
    const bool sheet = sequence_.config.shape == SyntheticShape::RolledSheet;
    return std::string(sheet ? "synthetic rolled sheet, " : "synthetic bending tube, ") +
           std::to_string(size()) + " frames of " +
           std::to_string(sequence_.rest.num_vertices()) + " vertices, generated into " +
           dir_.string() + " (ground truth in " + ground_truth_dir_.string() + ")";
  }
  json report() const override {
    json r = ObjFolderSource::report();
    r["kind"] = "synthetic";
    return r;
  }
  bool needs_check() const override { return false; }
  TriMesh template_frame(int i) const override {
    return TriMesh{synthetic_frame(sequence_, i).drifted, sequence_.F};
  }
  void prepare() const override { write_synthetic_sequence(sequence_, dir_, ground_truth_dir_); }
  fs::path ground_truth_dir() const override { return ground_truth_dir_; }
  SourceFrame decode(int i, std::string bytes) const override {
    SourceFrame frame = ObjFolderSource::decode(i, std::move(bytes));
    frame.ground_truth = synthetic_frame(sequence_, i).clean;
    return frame;
  }

 private:
  SyntheticSequence sequence_;
  fs::path ground_truth_dir_;
};

// ---------------------------------------------------------------------------------------------
// A glTF animation: frames evaluated on the welded connectivity when they are decoded.

class GltfSource : public FrameSource {
 public:
  explicit GltfSource(const GltfInputOptions& options)
      : options_(options),
        asset_(std::make_shared<const GltfSequence>(load_gltf_sequence(options))),
        sequence_(*asset_) {
    const std::string comment = "seqmassage: " + what() + "\nvertices welded by position; " +
                                "vt = (u, 1 - v) of TEXCOORD_0";
    layout_ = std::make_shared<const ObjFile>(gltf_obj_layout(sequence_, comment));
  }

  std::shared_ptr<const GltfSequence> asset() const { return asset_; }

  int size() const override { return sequence_.num_frames(); }
  std::string name(int i) const override { return numbered_frame_name(i, size()); }
  std::optional<double> time(int i) const override { return sequence_.times[size_t(i)]; }
  std::string describe() const override {
    const GltfSequence& s = sequence_;
    std::string text = "glTF " + what() + ", " + std::to_string(size()) + " frames ";
    text += options_.fps ? "at " + short_number(*options_.fps) + " fps" : "at the keyframe times";
    text += " (" + short_number(s.times.front()) + " to " + short_number(s.times.back()) + " s); " +
            std::to_string(s.gltf_vertices) + " glTF vertices welded to " +
            std::to_string(s.rest.num_vertices()) + " (" + std::to_string(s.welded_vertices) +
            " split copies merged";
    if (s.unreferenced_vertices > 0)
      text += ", " + std::to_string(s.unreferenced_vertices) + " in no triangle left out";
    if (s.dropped_triangles > 0)
      text += ", " + std::to_string(s.dropped_triangles) + " collapsed triangles dropped";
    return text + ")";
  }
  json report() const override {
    const GltfSequence& s = sequence_;
    return {{"kind", "gltf"},
            {"file", s.file.string()},
            {"mesh", s.mesh},
            {"mesh_name", s.mesh_name},
            {"node", s.node},
            {"animation", s.animation},
            {"animation_name", s.animation_name},
            {"fps", options_.fps ? json(*options_.fps) : json(nullptr)},
            {"frames", size()},
            {"time_start", s.times.front()},
            {"time_end", s.times.back()},
            {"gltf_vertices", s.gltf_vertices},
            {"vertices", s.rest.num_vertices()},
            {"welded_vertices", s.welded_vertices},
            {"unreferenced_vertices", s.unreferenced_vertices},
            {"dropped_triangles", s.dropped_triangles},
            {"triangles", s.rest.num_triangles()}};
  }
  std::vector<fs::path> files(const std::vector<int>&) const override {
    // The files the loader read (URIs percent-decoded and checked), so the hash covers them.
    std::vector<fs::path> out = {sequence_.file};
    const std::vector<fs::path>& resources = sequence_.scene->file.resources;
    out.insert(out.end(), resources.begin(), resources.end());
    return out;
  }
  TriMesh template_frame(int i) const override { return decode(i, {}).mesh; }
  std::string input_hash(int i, const std::string&) const override {
    std::call_once(asset_hash_once_, [&] {
      Sha256 hash;
      for (const fs::path& file : files({})) {
        const std::string part = file.filename().string() + " " + sha256_file(file) + "\n";
        hash.update(part);
      }
      asset_hash_ = hash.hex();
    });
    return sha256_hex(asset_hash_ + " frame " + std::to_string(i));
  }
  SourceFrame decode(int i, std::string) const override {
    const WeldedFrame f = evaluate_gltf_frame(sequence_, i);
    for (Eigen::Index v = 0; v < f.V.rows(); ++v) {
      if (!f.V.row(v).allFinite())
        throw InputError(
            "'" + sequence_.file.string() + "': " + element("animations", sequence_.animation) +
            " at t = " + short_number(sequence_.times[size_t(i)]) + " s (frame " +
            std::to_string(i) + "): " + element("meshes", sequence_.mesh) +
            " evaluates to a non-finite position at welded vertex " + std::to_string(v));
      if (f.V.row(v).cwiseAbs().maxCoeff() > kMaxCoordinate)
        throw InputError(
            "'" + sequence_.file.string() + "': " + element("animations", sequence_.animation) +
            " at t = " + short_number(sequence_.times[size_t(i)]) + " s (frame " +
            std::to_string(i) + "): " + element("meshes", sequence_.mesh) +
            " evaluates to a position of " + short_number(f.V.row(v).cwiseAbs().maxCoeff()) +
            " at welded vertex " + std::to_string(v) +
            ", more than 1e18 in magnitude (the geometry would overflow)");
    }
    SourceFrame frame;
    frame.mesh = TriMesh{f.V, sequence_.rest.F};
    frame.obj = layout_;
    if (f.separated_vertices > 0)
      frame.warnings.push_back(
          std::to_string(f.separated_vertices) +
          " welded vertices whose glTF copies lie apart (up to " + short_number(f.max_separation) +
          "; their skin weights or morph targets differ): each gets the mean of its copies");
    return frame;
  }

 private:
  static std::string element(const char* array, int index) {
    return std::string(array) + "[" + std::to_string(index) + "]";
  }
  // "take.glb, mesh 0 'body' (node 3), animation 1 'walk'"
  std::string what() const {
    const GltfSequence& s = sequence_;
    const auto named = [](const std::string& name) {
      return name.empty() ? std::string() : " '" + name + "'";
    };
    return s.file.filename().string() + ", mesh " + std::to_string(s.mesh) + named(s.mesh_name) +
           " (node " + std::to_string(s.node) + "), animation " + std::to_string(s.animation) +
           named(s.animation_name);
  }

  GltfInputOptions options_;
  std::shared_ptr<const GltfSequence> asset_;
  const GltfSequence& sequence_;
  std::shared_ptr<const ObjFile> layout_;
  mutable std::once_flag asset_hash_once_;
  mutable std::string asset_hash_;  // of the .glb/.gltf and the files it refers to
};

}  // namespace

std::shared_ptr<const FrameSource> make_frame_source(const SequenceJobOptions& config,
                                                     std::shared_ptr<const GltfSequence>* gltf) {
  for (const InputKind& kind : input_kinds())
    if (kind.given(config.input)) return kind.make(config, gltf);
  throw std::logic_error("make_frame_source: no input (the config check requires one)");
}

const std::vector<InputKind>& input_kinds() {
  static const std::vector<InputKind> kinds = {
      {"frames", "a folder of OBJ frames", "a folder of OBJ frames, in natural order",
       [](const InputOptions& in) { return !in.frames.empty(); },
       [](const SequenceJobOptions& c, std::shared_ptr<const GltfSequence>*)
           -> std::shared_ptr<const FrameSource> {
         return std::make_shared<ObjFolderSource>(c.input.frames);
       }},
      {"synthetic", "a generated sequence",
       "a generated drifted sequence (a bending tube) with its ground truth",
       [](const InputOptions& in) { return in.synthetic.has_value(); },
       [](const SequenceJobOptions& c, std::shared_ptr<const GltfSequence>*)
           -> std::shared_ptr<const FrameSource> {
         return std::make_shared<SyntheticSource>(*c.input.synthetic, c.output.dir);
       }},
      {"gltf", "a glTF animation",
       "a glTF 2.0 animation (.gltf or .glb), with \"mesh\", \"animation\", \"fps\"",
       [](const InputOptions& in) { return in.gltf.has_value(); },
       [](const SequenceJobOptions& c, std::shared_ptr<const GltfSequence>* gltf)
           -> std::shared_ptr<const FrameSource> {
         auto source = std::make_shared<GltfSource>(*c.input.gltf);
         if (gltf) *gltf = source->asset();
         return source;
       }},
      {"pc2", "a PC2 point cache, with its \"mesh\"",
       "a PC2 point cache on a mesh (\"mesh\": its OBJ, PLY or OFF)",
       [](const InputOptions& in) { return in.pc2.has_value(); },
       [](const SequenceJobOptions& c, std::shared_ptr<const GltfSequence>*) {
         return make_point_cache_source(*c.input.point_cache());
       }},
      {"mdd", "an MDD point cache, with its \"mesh\"",
       "an MDD point cache on a mesh (\"mesh\", as for \"pc2\")",
       [](const InputOptions& in) { return in.mdd.has_value(); },
       [](const SequenceJobOptions& c, std::shared_ptr<const GltfSequence>*) {
         return make_point_cache_source(*c.input.point_cache());
       }},
  };
  return kinds;
}

const std::string& input_kinds_text() {
  static const std::string text = [] {
    const std::vector<InputKind>& kinds = input_kinds();
    std::string t = "one of ";
    for (size_t k = 0; k < kinds.size(); ++k)
      t += std::string(k == 0 ? "" : k + 1 == kinds.size() ? " or " : ", ") + "\"" +
           kinds[k].key + "\" (" + kinds[k].what + ")";
    return t;
  }();
  return text;
}

std::string inputs_help() {
  std::string text;
  for (const InputKind& kind : input_kinds()) {
    std::string key = "  \"" + std::string(kind.key) + "\"";
    key.resize(std::max<size_t>(key.size() + 1, 30), ' ');
    text += key + kind.help + "\n";
  }
  return text;
}

}  // namespace sm
