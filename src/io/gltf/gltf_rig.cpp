#include "io/gltf/gltf_rig.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "io/gltf/gltf_accessor.hpp"

namespace sm {
namespace {

Eigen::Matrix4d compose(const Eigen::Vector3d& t, const Eigen::Vector4d& r,
                        const Eigen::Vector3d& s) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  const Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
  m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix() * s.asDiagonal();
  m.topRightCorner<3, 1>() = t;
  return m;
}

std::string node_name(size_t n) {
  return "nodes[" + std::to_string(n) + "]";
}

int morph_target_count(const tinygltf::Model& m, int mesh) {
  if (mesh < 0 || size_t(mesh) >= m.meshes.size() || m.meshes[size_t(mesh)].primitives.empty()) {
    return 0;
  }
  return int(m.meshes[size_t(mesh)].primitives[0].targets.size());
}

void load_nodes(const GltfFile& file, GltfRig& rig) {
  const tinygltf::Model& m = file.model;
  const size_t n = m.nodes.size();
  rig.parent.assign(n, -1);
  rig.rest_local.resize(n);
  rig.rest_translation.assign(n, Eigen::Vector3d::Zero());
  rig.rest_rotation.assign(n, Eigen::Vector4d(0, 0, 0, 1));
  rig.rest_scale.assign(n, Eigen::Vector3d::Ones());
  rig.rest_weights.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const tinygltf::Node& node = m.nodes[i];
    const auto check_size = [&](const std::vector<double>& v, size_t size, const char* what) {
      if (!v.empty() && v.size() != size) {
        throw_gltf_error(file.path, node_name(i),
                         std::string(what) + " has " + std::to_string(v.size()) +
                             " numbers, expected " + std::to_string(size));
      }
      for (double x : v) {
        if (!std::isfinite(x))
          throw_gltf_error(file.path, node_name(i), std::string(what) + " is not finite");
      }
    };
    check_size(node.translation, 3, "translation");
    check_size(node.rotation, 4, "rotation");
    check_size(node.scale, 3, "scale");
    check_size(node.matrix, 16, "matrix");
    if (node.mesh >= int(m.meshes.size())) {
      throw_gltf_error(file.path, node_name(i),
                       "mesh " + std::to_string(node.mesh) + " does not exist");
    }
    if (node.skin >= int(m.skins.size())) {
      throw_gltf_error(file.path, node_name(i),
                       "skin " + std::to_string(node.skin) + " does not exist");
    }
    if (!node.translation.empty())
      rig.rest_translation[i] = Eigen::Vector3d(node.translation.data());
    if (!node.rotation.empty()) rig.rest_rotation[i] = Eigen::Vector4d(node.rotation.data());
    if (!node.scale.empty()) rig.rest_scale[i] = Eigen::Vector3d(node.scale.data());
    rig.rest_local[i] =
        node.matrix.empty()
            ? compose(rig.rest_translation[i], rig.rest_rotation[i], rig.rest_scale[i])
            : Eigen::Matrix4d(Eigen::Map<const Eigen::Matrix4d>(node.matrix.data()));
    const int targets = morph_target_count(m, node.mesh);
    const std::vector<double>& mesh_weights =
        node.mesh >= 0 ? m.meshes[size_t(node.mesh)].weights : std::vector<double>{};
    rig.rest_weights[i] = !node.weights.empty() ? node.weights : mesh_weights;
    if (rig.rest_weights[i].empty()) rig.rest_weights[i].assign(size_t(targets), 0.0);
    if (int(rig.rest_weights[i].size()) != targets) {
      throw_gltf_error(file.path, node_name(i),
                       "has " + std::to_string(rig.rest_weights[i].size()) +
                           " morph weights for a mesh with " + std::to_string(targets) +
                           " morph targets");
    }
    for (int child : node.children) {
      if (child < 0 || size_t(child) >= n) {
        throw_gltf_error(file.path, node_name(i),
                         "child " + std::to_string(child) + " does not exist");
      }
      if (rig.parent[size_t(child)] != -1) {
        throw_gltf_error(file.path, node_name(size_t(child)), "has more than one parent");
      }
      rig.parent[size_t(child)] = int(i);
    }
  }
  for (size_t i = 0; i < n; ++i) {
    size_t steps = 0;
    for (int p = rig.parent[i]; p != -1; p = rig.parent[size_t(p)]) {
      if (++steps > n) throw_gltf_error(file.path, node_name(i), "lies on a cycle of children");
    }
  }
}

GltfKeyframes load_sampler(const GltfFile& file, const tinygltf::Animation& anim, int a, int s,
                           const std::string& path, int width) {
  const std::string element =
      "animations[" + std::to_string(a) + "].samplers[" + std::to_string(s) + "]";
  if (s < 0 || size_t(s) >= anim.samplers.size()) {
    throw_gltf_error(file.path, "animations[" + std::to_string(a) + "]",
                     "sampler " + std::to_string(s) + " does not exist");
  }
  const tinygltf::AnimationSampler& sampler = anim.samplers[size_t(s)];
  GltfKeyframes keys;
  keys.width = width;
  keys.rotation = path == "rotation";
  if (sampler.interpolation == "LINEAR") {
    keys.interpolation = GltfInterpolation::kLinear;
  } else if (sampler.interpolation == "STEP") {
    keys.interpolation = GltfInterpolation::kStep;
  } else if (sampler.interpolation == "CUBICSPLINE") {
    keys.interpolation = GltfInterpolation::kCubicSpline;
  } else {
    throw_gltf_error(file.path, element, "unknown interpolation '" + sampler.interpolation + "'");
  }
  keys.times =
      read_gltf_accessor(file, sampler.input, gltf_rules::kTime, element + ".input").values;
  for (size_t k = 1; k < keys.times.size(); ++k) {
    if (!(keys.times[k] > keys.times[k - 1])) {
      throw_gltf_error(file.path, element,
                       "input times are not strictly increasing at key " + std::to_string(k));
    }
  }
  const GltfAccessorRule& rule = path == "rotation"  ? gltf_rules::kRotationOutput
                                 : path == "weights" ? gltf_rules::kWeightsOutput
                                                     : gltf_rules::kVec3Output;
  keys.values = read_gltf_accessor(file, sampler.output, rule, element + ".output").values;
  const size_t groups = keys.interpolation == GltfInterpolation::kCubicSpline ? 3 : 1;
  if (keys.times.empty() || keys.values.size() != keys.times.size() * groups * size_t(width)) {
    throw_gltf_error(file.path, element,
                     "output has " + std::to_string(keys.values.size()) + " numbers for " +
                         std::to_string(keys.times.size()) + " keyframes of " + path +
                         " (expected " +
                         std::to_string(keys.times.size() * groups * size_t(width)) + ")");
  }
  if (keys.rotation) {
    // Keyframe rotations are unit quaternions; normalize what quantization or rounding moved off.
    for (size_t k = 0; k < keys.times.size(); ++k) {
      double* q = keys.values.data() + (groups == 3 ? 3 * k + 1 : k) * 4;
      const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (norm == 0)
        throw_gltf_error(file.path, element, "zero quaternion at key " + std::to_string(k));
      for (int c = 0; c < 4; ++c) q[c] /= norm;
    }
  }
  return keys;
}

void load_channels(const GltfFile& file, int a, GltfRig& rig) {
  const tinygltf::Model& m = file.model;
  if (a < 0 || size_t(a) >= m.animations.size()) {
    throw_gltf_error(file.path, "animations[" + std::to_string(a) + "]", "does not exist");
  }
  const tinygltf::Animation& anim = m.animations[size_t(a)];
  rig.tracks.assign(m.nodes.size(), GltfNodeTrack{});
  for (size_t c = 0; c < anim.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = anim.channels[c];
    const std::string element =
        "animations[" + std::to_string(a) + "].channels[" + std::to_string(c) + "]";
    if (ch.target_node < 0) continue;  // no target node: the channel is to be ignored (§3.11)
    if (size_t(ch.target_node) >= m.nodes.size()) {
      throw_gltf_error(file.path, element,
                       "target node " + std::to_string(ch.target_node) + " does not exist");
    }
    const tinygltf::Node& node = m.nodes[size_t(ch.target_node)];
    GltfNodeTrack& track = rig.tracks[size_t(ch.target_node)];
    const std::string& path = ch.target_path;
    std::optional<GltfKeyframes>* slot = path == "translation" ? &track.translation
                                         : path == "rotation"  ? &track.rotation
                                         : path == "scale"     ? &track.scale
                                         : path == "weights"   ? &track.weights
                                                               : nullptr;
    if (slot == nullptr) throw_gltf_error(file.path, element, "unknown target path '" + path + "'");
    if (path != "weights" && !node.matrix.empty()) {
      throw_gltf_error(file.path, element,
                       "animates the " + path + " of " + node_name(size_t(ch.target_node)) +
                           ", which has a matrix");
    }
    int width = path == "rotation" ? 4 : 3;
    if (path == "weights") {
      width = morph_target_count(m, node.mesh);
      if (width == 0) {
        throw_gltf_error(file.path, element,
                         "animates the weights of " + node_name(size_t(ch.target_node)) +
                             ", which has no morph targets");
      }
    }
    if (slot->has_value()) {
      throw_gltf_error(
          file.path, element,
          "a second channel for the " + path + " of " + node_name(size_t(ch.target_node)));
    }
    *slot = load_sampler(file, anim, int(a), ch.sampler, path, width);
    rig.keyframe_times.insert(rig.keyframe_times.end(), (*slot)->times.begin(),
                              (*slot)->times.end());
  }
  std::sort(rig.keyframe_times.begin(), rig.keyframe_times.end());
  rig.keyframe_times.erase(std::unique(rig.keyframe_times.begin(), rig.keyframe_times.end()),
                           rig.keyframe_times.end());
}

}  // namespace

GltfRig load_gltf_rig(const GltfFile& file, int animation) {
  GltfRig rig;
  load_nodes(file, rig);
  if (animation >= 0) load_channels(file, animation, rig);
  return rig;
}

std::vector<Eigen::Matrix4d> gltf_world_transforms(const GltfRig& rig, double t) {
  const size_t n = rig.parent.size();
  std::vector<Eigen::Matrix4d> local(n);
  for (size_t i = 0; i < n; ++i) {
    const GltfNodeTrack* track = rig.tracks.empty() ? nullptr : &rig.tracks[i];
    if (track == nullptr || (!track->translation && !track->rotation && !track->scale)) {
      local[i] = rig.rest_local[i];
      continue;
    }
    const auto vec = [&](const std::optional<GltfKeyframes>& k, const auto& rest) {
      using V = std::decay_t<decltype(rest)>;
      if (!k) return V(rest);
      return V(sample_keyframes(*k, t).data());
    };
    local[i] =
        compose(vec(track->translation, rig.rest_translation[i]),
                vec(track->rotation, rig.rest_rotation[i]), vec(track->scale, rig.rest_scale[i]));
  }
  // Parents before children: resolve each node's chain of not yet computed ancestors.
  std::vector<Eigen::Matrix4d> world(n);
  std::vector<char> done(n, 0);
  std::vector<size_t> chain;
  for (size_t i = 0; i < n; ++i) {
    chain.clear();
    for (int j = int(i); j != -1 && !done[size_t(j)]; j = rig.parent[size_t(j)])
      chain.push_back(size_t(j));
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const int p = rig.parent[*it];
      world[*it] = p == -1 ? local[*it] : Eigen::Matrix4d(world[size_t(p)] * local[*it]);
      done[*it] = 1;
    }
  }
  return world;
}

std::vector<double> gltf_morph_weights(const GltfRig& rig, int node, double t) {
  const size_t i = size_t(node);
  if (!rig.tracks.empty() && rig.tracks[i].weights)
    return sample_keyframes(*rig.tracks[i].weights, t);
  return rig.rest_weights[i];
}

}  // namespace sm
