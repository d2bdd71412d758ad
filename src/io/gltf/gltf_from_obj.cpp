#include "io/gltf/gltf_from_obj.hpp"

#include <tiny_gltf.h>

#include <map>

#include "core/errors.hpp"
#include "io/gltf/gltf_file.hpp"
#include "io/gltf/gltf_glb.hpp"
#include "io/gltf/gltf_weld.hpp"

namespace sm {
namespace {

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// The glTF vertices: one per distinct (v, vt) pair, in the order of their first corner, and the
// triangles over them (faces fanned as parse_obj fans them, so triangle t is obj.mesh.F's row t).
struct ObjCorners {
  std::vector<ObjCorner> vertices;
  std::vector<uint32_t> indices;
};

ObjCorners corner_vertices(const ObjFile& obj) {
  ObjCorners out;
  std::map<std::pair<int, int>, uint32_t> id;
  const auto vertex = [&](const ObjCorner& c) {
    const auto [at, fresh] = id.emplace(std::pair{c.v, c.vt}, uint32_t(out.vertices.size()));
    if (fresh) out.vertices.push_back(c);
    return at->second;
  };
  for (int f = 0; f < obj.num_faces(); ++f) {
    const int first = obj.face_offsets[size_t(f)];
    const int n = obj.face_offsets[size_t(f) + 1] - first;
    for (int k = 1; k + 1 < n; ++k)
      for (int c : {first, first + k, first + k + 1})
        out.indices.push_back(vertex(obj.corners[size_t(c)]));
  }
  return out;
}

// Unit normals of `obj`'s `v` rows: the welded surface's area-weighted normals; +z where a
// vertex has no area (glTF requires unit NORMAL values).
Positions obj_vertex_normals(const ObjFile& obj) {
  const GltfWeld weld = weld_by_position(obj.mesh.V, obj.mesh.F);
  const Positions welded = vertex_normals(weld.mesh);
  Positions N = Positions::Zero(obj.mesh.V.rows(), 3);
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const int w = weld.map[size_t(i)];
    if (w >= 0) N.row(i) = welded.row(w);
    if (N.row(i).squaredNorm() < 0.5) N.row(i) = Eigen::RowVector3d(0, 0, 1);
  }
  return N;
}

std::string obj_glb(const ObjFile& obj, const ObjCorners& corners,
                    const std::vector<double>& times) {
  const Positions N = obj_vertex_normals(obj);
  std::vector<float> position, normal, texcoord;
  for (const ObjCorner& c : corners.vertices) {
    for (int d = 0; d < 3; ++d) position.push_back(float(obj.mesh.V(c.v, d)));
    for (int d = 0; d < 3; ++d) normal.push_back(float(N(c.v, d)));
    if (!obj.has_texcoords()) continue;
    texcoord.push_back(c.vt >= 0 ? float(obj.texcoords(c.vt, 0)) : 0.0f);
    texcoord.push_back(c.vt >= 0 ? float(1.0 - obj.texcoords(c.vt, 1)) : 0.0f);
  }
  GlbBuilder glb;
  nlohmann::json attributes = {
      {"POSITION", glb.add_floats(position, TINYGLTF_TYPE_VEC3, kArrayBuffer, true)},
      {"NORMAL", glb.add_floats(normal, TINYGLTF_TYPE_VEC3, kArrayBuffer, false)}};
  if (!texcoord.empty())
    attributes["TEXCOORD_0"] = glb.add_floats(texcoord, TINYGLTF_TYPE_VEC2, kArrayBuffer, false);
  const int index_view = glb.add_view(corners.indices.data(),
                                      corners.indices.size() * sizeof(uint32_t),
                                      kElementArrayBuffer);
  const int indices = glb.add_accessor(index_view, 0, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                       TINYGLTF_TYPE_SCALAR, corners.indices.size(), false);
  const std::vector<float> keys(times.begin(), times.end());
  const int input = glb.add_floats(keys, TINYGLTF_TYPE_SCALAR, 0, true);
  const int output =
      glb.add_floats(std::vector<float>(3 * keys.size(), 0.0f), TINYGLTF_TYPE_VEC3, 0, false);

  nlohmann::json& doc = glb.document();
  doc["asset"] = {{"version", "2.0"}, {"generator", "seqmassage"}};
  doc["scene"] = 0;
  doc["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
  doc["nodes"] = nlohmann::json::array({{{"mesh", 0}, {"name", "template"}}});
  nlohmann::json primitive = {{"attributes", attributes}, {"indices", indices}};
  doc["meshes"] = nlohmann::json::array(
      {{{"name", "template"}, {"primitives", nlohmann::json::array({primitive})}}});
  nlohmann::json sampler = {{"input", input}, {"output", output}, {"interpolation", "LINEAR"}};
  nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}};
  nlohmann::json animation = {{"name", "frames"},
                              {"samplers", nlohmann::json::array({sampler})},
                              {"channels", nlohmann::json::array({channel})}};
  doc["animations"] = nlohmann::json::array({animation});
  return glb.finish();
}

}  // namespace

GltfSequence gltf_sequence_from_obj(const ObjFile& obj, const std::vector<double>& times,
                                    const std::string& name) {
  if (times.empty()) throw std::logic_error("gltf_sequence_from_obj: no frame time");
  const ObjCorners corners = corner_vertices(obj);
  if (corners.indices.empty()) throw InputError(name + ": no face to write as glTF");
  GltfInputOptions options;
  options.file = name;
  options.mesh_index = 0;
  options.animation_index = 0;
  GltfSequence s = gltf_sequence_of(parse_gltf_file(name, obj_glb(obj, corners, times)), options);
  s.rest_source.assign(size_t(s.rest.num_vertices()), -1);
  for (size_t g = 0; g < corners.vertices.size(); ++g)
    if (const int r = s.weld_map[g]; r >= 0) s.rest_source[size_t(r)] = corners.vertices[g].v;
  s.source_rows = int(obj.mesh.V.rows());
  return s;
}

}  // namespace sm
