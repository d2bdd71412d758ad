#include "io/gltf/gltf_skin_morph.hpp"

#include <string>

#include "io/gltf/gltf_accessor.hpp"

namespace sm {
namespace {

std::string primitive_name(int mesh, size_t p) {
  return "meshes[" + std::to_string(mesh) + "].primitives[" + std::to_string(p) + "]";
}

const char* mode_name(int mode) {
  static const char* names[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
  return mode >= 0 && mode < 4 ? names[mode] : "unknown";
}

/// Appends the primitive's triangles (glTF 2.0 §3.7.2.1 topology types) offset by `first`.
void append_triangles(const GltfFile& file, const tinygltf::Primitive& prim,
                      const std::string& name, int first, int vertex_count, std::vector<int>& out) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    throw_gltf_error(file.path, name,
                     std::string("mode ") + std::to_string(mode) + " (" + mode_name(mode) +
                         ") is not a triangle primitive");
  }
  std::vector<int> ids;
  if (prim.indices >= 0) {
    const GltfAccessorValues idx =
        read_gltf_accessor(file, prim.indices, gltf_rules::kIndices, name + ".indices");
    ids.reserve(size_t(idx.count));
    for (int k = 0; k < idx.count; ++k) {
      const double v = idx.values[size_t(k)];
      if (v >= vertex_count) {
        throw_gltf_error(file.path, "accessors[" + std::to_string(prim.indices) + "]",
                         "index " + std::to_string(uint64_t(v)) + " at position " +
                             std::to_string(k) + " is out of range for " + name + " (" +
                             std::to_string(vertex_count) + " vertices)");
      }
      ids.push_back(int(v));
    }
  } else {
    ids.resize(size_t(vertex_count));
    for (int k = 0; k < vertex_count; ++k) ids[size_t(k)] = k;
  }
  const size_t n = ids.size();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0) {
      throw_gltf_error(file.path, name,
                       std::to_string(n) + " vertex indices are not a multiple of 3");
    }
    for (size_t k = 0; k < n; ++k) out.push_back(first + ids[k]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i) {  // {v_i, v_i+(1+i%2), v_i+(2-i%2)}
      out.insert(out.end(),
                 {first + ids[i], first + ids[i + 1 + i % 2], first + ids[i + 2 - i % 2]});
    }
  } else {
    for (size_t i = 0; i + 2 < n; ++i) {  // {v_i+1, v_i+2, v_0}
      out.insert(out.end(), {first + ids[i + 1], first + ids[i + 2], first + ids[0]});
    }
  }
}

int attribute(const tinygltf::Primitive& prim, const std::string& name) {
  const auto it = prim.attributes.find(name);
  return it == prim.attributes.end() ? -1 : it->second;
}

void load_skin(const GltfFile& file, int skin, GltfMeshGeometry& g) {
  const tinygltf::Model& m = file.model;
  const std::string element = "skins[" + std::to_string(skin) + "]";
  const tinygltf::Skin& s = m.skins[size_t(skin)];
  g.skin = skin;
  g.joint_nodes = s.joints;
  if (g.joint_nodes.empty()) throw_gltf_error(file.path, element, "has no joints");
  for (int j : g.joint_nodes) {
    if (j < 0 || size_t(j) >= m.nodes.size()) {
      throw_gltf_error(file.path, element, "joint node " + std::to_string(j) + " does not exist");
    }
  }
  g.inverse_bind.assign(g.joint_nodes.size(), Eigen::Matrix4d::Identity());
  if (s.inverseBindMatrices >= 0) {
    const GltfAccessorValues ibm = read_gltf_accessor(
        file, s.inverseBindMatrices, gltf_rules::kMatrix, element + ".inverseBindMatrices");
    if (size_t(ibm.count) != g.joint_nodes.size()) {
      throw_gltf_error(file.path, element,
                       std::to_string(ibm.count) + " inverse bind matrices for " +
                           std::to_string(g.joint_nodes.size()) + " joints");
    }
    for (size_t j = 0; j < g.joint_nodes.size(); ++j) {
      g.inverse_bind[j] = Eigen::Map<const Eigen::Matrix4d>(ibm.values.data() + 16 * j);
    }
  }
}

/// Reads the JOINTS_n/WEIGHTS_n sets of one primitive into g.joints/g.weights.
void load_influences(const GltfFile& file, const tinygltf::Primitive& prim, const std::string& name,
                     const GltfPrimitiveRange& range, GltfMeshGeometry& g) {
  for (int set = 0;; ++set) {
    const int ja = attribute(prim, "JOINTS_" + std::to_string(set));
    const int wa = attribute(prim, "WEIGHTS_" + std::to_string(set));
    if (ja < 0 && wa < 0) {
      if (set == 0) throw_gltf_error(file.path, name, "skinned but has no JOINTS_0/WEIGHTS_0");
      return;
    }
    if (ja < 0 || wa < 0) {
      throw_gltf_error(
          file.path, name,
          "has only one of JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set));
    }
    const std::string sfx = "_" + std::to_string(set);
    const GltfAccessorValues J =
        read_gltf_accessor(file, ja, gltf_rules::kJoints, name + ".attributes.JOINTS" + sfx);
    const GltfAccessorValues W =
        read_gltf_accessor(file, wa, gltf_rules::kWeights, name + ".attributes.WEIGHTS" + sfx);
    if (J.count != range.vertex_count || W.count != range.vertex_count) {
      throw_gltf_error(file.path, name,
                       "JOINTS" + sfx + "/WEIGHTS" + sfx + " counts differ from POSITION's " +
                           std::to_string(range.vertex_count));
    }
    if (4 * (set + 1) > g.influences) {  // widen the n × influences tables, padding with weight 0
      const int wider = 4 * (set + 1);
      std::vector<int> joints(size_t(g.num_vertices()) * size_t(wider), 0);
      std::vector<double> weights(joints.size(), 0.0);
      for (int v = 0; v < g.num_vertices(); ++v) {
        for (int k = 0; k < g.influences; ++k) {
          joints[size_t(v * wider + k)] = g.joints[size_t(v * g.influences + k)];
          weights[size_t(v * wider + k)] = g.weights[size_t(v * g.influences + k)];
        }
      }
      g.joints.swap(joints);
      g.weights.swap(weights);
      g.influences = wider;
    }
    for (int v = 0; v < range.vertex_count; ++v) {
      for (int c = 0; c < 4; ++c) {
        const double joint = J.at(v, c);
        if (joint >= double(g.joint_nodes.size())) {
          throw_gltf_error(file.path, "accessors[" + std::to_string(ja) + "]",
                           "joint " + std::to_string(int(joint)) + " of vertex " +
                               std::to_string(v) + " is out of range for skins[" +
                               std::to_string(g.skin) + "] (" +
                               std::to_string(g.joint_nodes.size()) + " joints)");
        }
        const size_t at =
            size_t(range.first_vertex + v) * size_t(g.influences) + size_t(4 * set + c);
        g.joints[at] = int(joint);
        g.weights[at] = W.at(v, c);
      }
    }
  }
}

}  // namespace

GltfMeshGeometry load_gltf_mesh_geometry(const GltfFile& file, int mesh, int skin) {
  const tinygltf::Model& m = file.model;
  const tinygltf::Mesh& source = m.meshes[size_t(mesh)];
  const std::string mesh_element = "meshes[" + std::to_string(mesh) + "]";
  if (source.primitives.empty()) throw_gltf_error(file.path, mesh_element, "has no primitives");
  GltfMeshGeometry g;
  g.mesh = mesh;
  const size_t targets = source.primitives[0].targets.size();
  std::vector<GltfAccessorValues> positions;
  int total = 0;
  for (size_t p = 0; p < source.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = source.primitives[p];
    const std::string name = primitive_name(mesh, p);
    const int pa = attribute(prim, "POSITION");
    if (pa < 0) throw_gltf_error(file.path, name, "has no POSITION attribute");
    positions.push_back(
        read_gltf_accessor(file, pa, gltf_rules::kPosition, name + ".attributes.POSITION"));
    if (prim.targets.size() != targets) {
      throw_gltf_error(file.path, name,
                       "has " + std::to_string(prim.targets.size()) +
                           " morph targets, primitive 0 has " + std::to_string(targets));
    }
    g.primitives.push_back({total, positions.back().count});
    total += positions.back().count;
  }
  g.base.resize(total, 3);
  g.target_deltas.assign(targets, Positions::Zero(total, 3));
  std::vector<int> corners;
  for (size_t p = 0; p < source.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = source.primitives[p];
    const GltfPrimitiveRange& range = g.primitives[p];
    const std::string name = primitive_name(mesh, p);
    for (int v = 0; v < range.vertex_count; ++v) {
      for (int c = 0; c < 3; ++c) g.base(range.first_vertex + v, c) = positions[p].at(v, c);
    }
    for (size_t t = 0; t < targets; ++t) {
      const auto it = prim.targets[t].find("POSITION");
      if (it == prim.targets[t].end()) continue;  // this target does not move this primitive
      const std::string user = name + ".targets[" + std::to_string(t) + "].POSITION";
      const GltfAccessorValues d =
          read_gltf_accessor(file, it->second, gltf_rules::kPosition, user);
      if (d.count != range.vertex_count) {
        throw_gltf_error(file.path, name + ".targets[" + std::to_string(t) + "]",
                         "POSITION has " + std::to_string(d.count) + " elements, the primitive " +
                             std::to_string(range.vertex_count));
      }
      for (int v = 0; v < range.vertex_count; ++v) {
        for (int c = 0; c < 3; ++c) g.target_deltas[t](range.first_vertex + v, c) = d.at(v, c);
      }
    }
    append_triangles(file, prim, name, range.first_vertex, range.vertex_count, corners);
  }
  g.triangles = Eigen::Map<const Triangles>(corners.data(), Eigen::Index(corners.size() / 3), 3);
  if (skin >= 0) {
    load_skin(file, skin, g);
    for (size_t p = 0; p < source.primitives.size(); ++p) {
      load_influences(file, source.primitives[p], primitive_name(mesh, p), g.primitives[p], g);
    }
  }
  return g;
}

Positions gltf_mesh_positions(const GltfMeshGeometry& g, const GltfRig& rig, int node, double t) {
  Positions P = g.base;
  if (!g.target_deltas.empty()) {
    const std::vector<double> w = gltf_morph_weights(rig, node, t);
    for (size_t k = 0; k < g.target_deltas.size(); ++k) {
      if (w[k] != 0) P += w[k] * g.target_deltas[k];
    }
  }
  const std::vector<Eigen::Matrix4d> world = gltf_world_transforms(rig, t);
  if (g.skin < 0) {
    const Eigen::Matrix4d& M = world[size_t(node)];
    const Eigen::Matrix3d A = M.topLeftCorner<3, 3>();
    const Eigen::RowVector3d b = M.topRightCorner<3, 1>().transpose();
    return (P * A.transpose()).rowwise() + b;
  }
  // Joint matrix j = world(joint j) · inverseBind(j); p' = Σ weight · (joint matrix · p).
  std::vector<Eigen::Matrix<double, 3, 4>> joint(g.joint_nodes.size());
  for (size_t j = 0; j < joint.size(); ++j) {
    joint[j] = (world[size_t(g.joint_nodes[j])] * g.inverse_bind[j]).topRows<3>();
  }
  Positions out = Positions::Zero(P.rows(), 3);
  for (Eigen::Index v = 0; v < P.rows(); ++v) {
    const Eigen::Vector4d p(P(v, 0), P(v, 1), P(v, 2), 1.0);
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    for (int k = 0; k < g.influences; ++k) {
      const double w = g.weights[size_t(v) * size_t(g.influences) + size_t(k)];
      if (w != 0)
        q += w * (joint[size_t(g.joints[size_t(v) * size_t(g.influences) + size_t(k)])] * p);
    }
    out.row(v) = q.transpose();
  }
  return out;
}

}  // namespace sm
