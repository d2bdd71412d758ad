#pragma once
/// Where the frames of a sequence job come from: a folder of OBJ files, a generated synthetic
/// sequence, or a glTF animation sampled to frames. The pipeline reads every source alike: fetch
/// (in frame order, one at a time: file I/O) then decode (in parallel: parsing, glTF evaluation),
/// so that only the frames in flight are ever held in memory.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/gltf/gltf_load.hpp"
#include "io/obj.hpp"
#include "io/point_cache.hpp"
#include "mesh/mesh.hpp"

namespace sm {

/// One frame as read.
struct SourceFrame {
  TriMesh mesh;  ///< positions (n×3) and the triangles the optimizer sees (m×3)
  /// Everything an OBJ output writes besides the positions (texture coordinates, normals, groups,
  /// faces); its v statements match mesh.V's rows.
  std::shared_ptr<const ObjFile> obj;
  std::string bytes;  ///< the frame's file as read; empty when the frame has no file of its own
  std::vector<std::string> warnings;  ///< e.g. welded glTF copies that came apart
  /// The frame's clean positions (n×3), for a generated sequence (its ground truth).
  std::optional<Positions> ground_truth;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  /// Number of frames, all of them (input.range selects among them).
  virtual int size() const = 0;
  /// The frame's file name: the OBJ file's, or "frame_0007.obj" for a glTF frame (the name its
  /// OBJ output gets). summary.csv's `file`; output files are named after it.
  virtual std::string name(int i) const = 0;
  /// The frame's time in seconds, for an animation (glTF); nothing otherwise.
  virtual std::optional<double> time(int /*i*/) const { return std::nullopt; }
  /// The frame in messages: "frame 7 (frame_0007.obj)", with the time if it has one.
  std::string label(int i) const;
  /// One line for the plan, e.g. "15 OBJ frames in captures/take1".
  virtual std::string describe() const = 0;
  /// report.json "input": what was read, with counts (e.g. welded glTF vertices).
  virtual nlohmann::json report() const = 0;
  /// The files frames `frames` are read from (outputs must not overwrite them).
  virtual std::vector<std::filesystem::path> files(const std::vector<int>& frames) const = 0;

  /// Whether planning must read every selected frame to check it against the template (false
  /// for frames that are consistent by construction).
  virtual bool needs_check() const { return true; }
  /// Frame i as a template, read at planning time (before prepare()).
  virtual TriMesh template_frame(int i) const;
  /// Called once when a run starts, before the first fetch (e.g. writes generated frames).
  virtual void prepare() const {}
  /// The serial, in-order part of reading frame i (file I/O); "" when there is none.
  virtual std::string fetch(int i) const;
  /// The parallel part: frame i from what fetch returned. Thread-safe. Throws InputError naming
  /// the frame and the element at fault.
  virtual SourceFrame decode(int i, std::string bytes) const = 0;
  /// SHA-256 of everything frame i is made from, given what fetch returned: the bytes of its
  /// file, or for a glTF frame the asset's files with the frame's index. Thread-safe. A frame
  /// record keeps it, so that --resume redoes a frame whose input changed.
  virtual std::string input_hash(int i, const std::string& fetched) const;

  /// Where the clean frames of a generated sequence are written, empty if there are none.
  virtual std::filesystem::path ground_truth_dir() const { return {}; }
  /// The header of the point cache the frames are read from (PC2, MDD), or null.
  virtual const PointCacheHeader* point_cache() const { return nullptr; }
};

/// "frame 7 (frame_0007.obj)", with ", t = 0.25 s" for a frame with a time: how messages name a
/// A frame time as the labels and descriptions print it: "%.6g" ("0.0416667").
std::string short_number(double t);
/// frame (FrameSource::label).
std::string frame_label(int i, const std::string& name, std::optional<double> time);

/// "frame_0007.obj": frame i's name among `count` frames (at least 4 digits).
std::string numbered_frame_name(int i, int count);

}  // namespace sm
