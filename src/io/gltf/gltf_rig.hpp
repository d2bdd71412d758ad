#pragma once
/// The node hierarchy of a glTF asset and one animation's channels: local TRS or matrix per node,
/// parents, and the world transforms and morph weights at any time.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "io/gltf/gltf_animation.hpp"
#include "io/gltf/gltf_file.hpp"

namespace sm {

/// The animated properties of one node (absent = not animated).
struct GltfNodeTrack {
  std::optional<GltfKeyframes> translation, rotation, scale, weights;
};

struct GltfRig {
  std::vector<int> parent;                  ///< per node, -1 for a root
  std::vector<Eigen::Matrix4d> rest_local;  ///< node.matrix or T·R·S of the node's values
  std::vector<Eigen::Vector3d> rest_translation;
  std::vector<Eigen::Vector4d> rest_rotation;  ///< x, y, z, w
  std::vector<Eigen::Vector3d> rest_scale;
  std::vector<std::vector<double>> rest_weights;  ///< node.weights, else its mesh's, else zeros
  std::vector<GltfNodeTrack> tracks;              ///< per node; empty without an animation
  std::vector<double> keyframe_times;             ///< sorted union of all sampler inputs
};

/// Reads the nodes and, when `animation` >= 0, the channels of animations[animation]. Throws
/// InputError naming the node, channel, sampler or accessor for out-of-range indices, a node with
/// two parents or on a cycle, malformed TRS values, a matrix node targeted by a TRS channel, a
/// weights channel on a node without morph targets, or sampler data of the wrong shape.
GltfRig load_gltf_rig(const GltfFile& file, int animation);

/// World matrix of every node at time `t` (parent world · local, local = T·R·S with the animated
/// values replacing the node's own).
std::vector<Eigen::Matrix4d> gltf_world_transforms(const GltfRig& rig, double t);

/// Morph weights of `node` at time `t`: the animated weights if a channel targets them, else the
/// node's (or its mesh's) default weights.
std::vector<double> gltf_morph_weights(const GltfRig& rig, int node, double t);

}  // namespace sm
