#include "io/gltf/gltf_obj.hpp"

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "io/gltf/gltf_accessor.hpp"
#include "io/gltf/gltf_scene.hpp"
#include "io/text_scan.hpp"

namespace sm {
namespace {

const GltfAccessorRule kTexcoord{
    "TEXCOORD",
    {TINYGLTF_TYPE_VEC2},
    {TINYGLTF_COMPONENT_TYPE_FLOAT},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT}};

/// Attribute `name` of primitive `p`, decoded, or nothing when the primitive has none.
std::optional<GltfAccessorValues> attribute(const GltfFile& file, const tinygltf::Primitive& prim,
                                            const std::string& element, const char* name,
                                            const GltfAccessorRule& rule, int vertex_count) {
  const auto it = prim.attributes.find(name);
  if (it == prim.attributes.end()) return std::nullopt;
  const std::string user = element + ".attributes." + name;
  GltfAccessorValues values = read_gltf_accessor(file, it->second, rule, user);
  if (values.count != vertex_count) {
    throw_gltf_error(file.path, user,
                     std::to_string(values.count) + " elements, but POSITION has " +
                         std::to_string(vertex_count));
  }
  return values;
}

void append_row(std::string& text, const char* keyword, std::initializer_list<double> values) {
  text += keyword;
  for (double x : values) {
    text += ' ';
    append_double(text, x + 0.0);  // -0 written as 0
  }
  text += '\n';
}

}  // namespace

ObjFile gltf_obj_layout(const GltfSequence& sequence, const std::string& comment) {
  const GltfScene& scene = *sequence.scene;
  const GltfFile& file = scene.file;
  const GltfMeshGeometry& g = scene.geometry;
  const tinygltf::Mesh& mesh = file.model.meshes[size_t(sequence.mesh)];
  const std::vector<int>& weld = sequence.weld_map;

  std::string text;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) text += "# " + line + "\n";
  const Positions& rest = sequence.rest.V;
  for (Eigen::Index i = 0; i < rest.rows(); ++i)
    append_row(text, "v", {rest(i, 0), rest(i, 1), rest(i, 2)});

  // Per glTF vertex, its vt and vn (0-based, -1 for none).
  std::vector<int> vt(size_t(g.num_vertices()), -1), vn(size_t(g.num_vertices()), -1);
  int vt_count = 0;
  std::map<std::tuple<int, double, double, double>, int> normals;
  for (size_t p = 0; p < g.primitives.size(); ++p) {
    const GltfPrimitiveRange& r = g.primitives[p];
    const std::string element =
        "meshes[" + std::to_string(sequence.mesh) + "].primitives[" + std::to_string(p) + "]";
    const tinygltf::Primitive& prim = mesh.primitives[p];
    if (const auto uv = attribute(file, prim, element, "TEXCOORD_0", kTexcoord, r.vertex_count)) {
      for (int v = 0; v < r.vertex_count; ++v) {
        vt[size_t(r.first_vertex + v)] = vt_count++;
        append_row(text, "vt", {uv->at(v, 0), 1.0 - uv->at(v, 1)});
      }
    }
    const auto n = attribute(file, prim, element, "NORMAL", gltf_rules::kNormal, r.vertex_count);
    for (int v = 0; n && v < r.vertex_count; ++v) {
      const int w = weld[size_t(r.first_vertex + v)];
      if (w < 0) continue;
      const auto key = std::make_tuple(w, n->at(v, 0), n->at(v, 1), n->at(v, 2));
      const auto [it, added] = normals.emplace(key, int(normals.size()));
      if (added) append_row(text, "vn", {n->at(v, 0), n->at(v, 1), n->at(v, 2)});
      vn[size_t(r.first_vertex + v)] = it->second;
    }
  }

  // Faces: the welded triangles, in the order weld_by_position keeps them.
  const auto primitive_of = [&](int vertex) {
    const auto after =
        std::upper_bound(g.primitives.begin(), g.primitives.end(), vertex,
                         [](int x, const GltfPrimitiveRange& r) { return x < r.first_vertex; });
    return int(after - g.primitives.begin()) - 1;
  };
  int group = -1;
  for (Eigen::Index t = 0; t < g.triangles.rows(); ++t) {
    const int a = g.triangles(t, 0), b = g.triangles(t, 1), c = g.triangles(t, 2);
    const int wa = weld[size_t(a)], wb = weld[size_t(b)], wc = weld[size_t(c)];
    if (wa == wb || wb == wc || wc == wa) continue;  // collapsed by welding
    if (const int p = primitive_of(a); p != group) {
      group = p;
      text += "g primitive_" + std::to_string(p) + "\n";
    }
    text += 'f';
    for (const int v : {a, b, c}) {
      text += ' ';
      append_int(text, weld[size_t(v)] + 1);
      if (vt[size_t(v)] >= 0 || vn[size_t(v)] >= 0) text += '/';
      if (vt[size_t(v)] >= 0) append_int(text, vt[size_t(v)] + 1);
      if (vn[size_t(v)] >= 0) {
        text += '/';
        append_int(text, vn[size_t(v)] + 1);
      }
    }
    text += '\n';
  }

  ObjFile layout = parse_obj(text, file.path.filename().string() + " (as OBJ)");
  if (layout.mesh.F != sequence.rest.F)
    throw std::logic_error("gltf_obj_layout: the OBJ faces differ from the welded triangles");
  return layout;
}

}  // namespace sm
