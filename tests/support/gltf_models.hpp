#pragma once
/// glTF assets built in code for the glTF tests (written with tinygltf), whose animated positions
/// are known in closed form, the shared Khronos sample models, and the Khronos validator, when
/// installed.
#include <tiny_gltf.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace sm::test {

/// A tinygltf model with one buffer that accessors are appended to.
struct ModelBuilder {
  tinygltf::Model m;
  ModelBuilder();

  int view(const void* data, size_t bytes, int target = 0, int stride = 0);
  int accessor(int view, int component_type, int type, size_t count, bool normalized = false,
               size_t byte_offset = 0);
  int floats(const std::vector<float>& values, int type, int target = 0);
  int ubytes(const std::vector<uint8_t>& values, int type, bool normalized, int target = 0);
  int ushorts(const std::vector<uint16_t>& values, int type, bool normalized, int target = 0);
  int node(const std::string& name);
  /// Adds a sampler and a channel to animations[0] (created on first use).
  void channel(int node, const std::string& path, const std::vector<float>& times,
               const std::vector<float>& values, const std::string& interpolation);
  /// Writes a GLB (`binary`) or a .gltf with an external .bin next to it.
  void save(const std::filesystem::path& file, bool binary) const;
};

/// Knobs of the morph-target quad: interpolation of its weights and their component type.
struct MorphQuadOptions {
  std::string interpolation = "LINEAR";
  bool ubyte_weights = false;  ///< weights output as normalized UNSIGNED_BYTE
  bool sparse_target = true;   ///< target 1 as a sparse accessor without buffer view
};

/// Unit quad at z = 0 (NORMAL (0, 0, 1), TANGENT (1, 0, 0, 1)) under a node translated by (1, 2,
/// 3). Target 0 lifts vertex 2 by (0, 0, 1); target 1 lifts vertex 3 by (0, 0, 2). Weights keys at
/// t = 0, 1, 2: (0, 0), (1, 0.5), (0, 1) (CUBICSPLINE: the same values with zero tangents). Mesh
/// default weights (0.5, 0).
ModelBuilder morph_quad(const MorphQuadOptions& options = {});

/// Closed form of morph_quad's weights at time t.
std::vector<double> morph_quad_weights(const MorphQuadOptions& options, double t);

/// Triangle (0,0,0), (1,0,0), (0,1,0) on a child node translated by (1, 0, 0) under a parent
/// whose rotation about z goes LINEAR from 0 to 170 degrees over t in [0, 1], and whose
/// translation is CUBICSPLINE from (0,0,0) at t = 0 to (2,0,0) at t = 2 with out-tangent (3,0,0)
/// and in-tangent 0, and whose scale steps (STEP) from 1 to 2 at t = 1.5.
ModelBuilder node_animated_triangle();

/// Two-bone strip: vertices (x, y) for x in {0, 0.5, 1, 1.5, 2}, y in {0, 1}, the x = 1 column
/// split in two copies (UV seam: u = 0.5 and u = 0.6), 4 quads. Joints: bone0 at the origin and
/// its child bone1 at (1, 0, 0), under an armature node translated by (0, 0, 5); inverse bind
/// matrices undo the bind pose. Weights: bone1 weight 0 for x < 1, 0.5 at x = 1 (first set only,
/// or split across JOINTS_1/WEIGHTS_1 with `two_sets`), 1 for x > 1. bone1 rotates about z LINEAR
/// from 0 to 90 degrees over t in [0, 1]. The mesh node carries a translation that skinning must
/// ignore. A material with a base colour texture (a 1×1 PNG) uses TEXCOORD_0.
ModelBuilder skinned_strip(bool two_sets = false);

/// ../shared/data/gltf: the Khronos sample models of data/README.md §2.
std::filesystem::path shared_gltf_dir();

/// Whether shared_gltf_dir() is present; if not, WARNs that the test is skipped.
bool have_shared_gltf();

/// An animated model of shared_gltf_dir() with the facts the tests check (data/README.md §2).
struct SharedGltfModel {
  const char* file;  ///< under shared_gltf_dir()
  int gltf_vertices;
  int welded_vertices;  ///< rest.num_vertices()
  int triangles;
  int frames;          ///< default sampling: the keyframe times of the first animation
  int boundary_loops;  ///< of the welded mesh
};

/// Every animated model of the shared data (CesiumMan twice: GLB and .gltf + .bin + .jpg).
extern const SharedGltfModel kSharedGltfModels[10];

/// The shared models without animation (under shared_gltf_dir()): Box, BoxTextured, and
/// MorphPrimitivesTest (morph targets, static weights).
extern const char* const kStaticGltfModels[3];

/// Runs tools/validate_gltf.js on `file`. Returns the number of errors (with the report in
/// `report`), or nothing when node or the gltf-validator package is missing (`report` says why).
std::optional<int> validate_gltf(const std::filesystem::path& file, std::string& report);

/// Requires |got - expected| <= rel · max(1, max |expected|) coordinate by coordinate.
void require_close(const Positions& got, const Positions& expected, double rel = 1e-6);

/// Requires zero validator errors for `file`; WARNs and returns when the validator is unavailable.
void require_valid_gltf(const std::filesystem::path& file);

}  // namespace sm::test
