#pragma once
/// Decoding glTF accessors: every component type, normalized integers, byte strides, matrix column
/// padding and sparse substitution, bounds-checked, with errors that name the accessor.
#include <cstdint>
#include <string>
#include <vector>

#include "io/gltf/gltf_file.hpp"

namespace sm {

/// What a use of an accessor allows (glTF 2.0 §3.7.2.1, §3.11 and KHR_mesh_quantization).
struct GltfAccessorRule {
  const char* role;                  ///< for messages, e.g. "POSITION"
  std::vector<int> types;            ///< TINYGLTF_TYPE_* allowed
  std::vector<int> float_or_int;     ///< component types allowed with normalized = false
  std::vector<int> normalized_ints;  ///< component types allowed with normalized = true
};

/// Rules of the attributes and animation data this project reads.
namespace gltf_rules {
extern const GltfAccessorRule kPosition;        ///< POSITION and morph-target POSITION
extern const GltfAccessorRule kNormal;          ///< NORMAL
extern const GltfAccessorRule kTangent;         ///< TANGENT
extern const GltfAccessorRule kJoints;          ///< JOINTS_n
extern const GltfAccessorRule kWeights;         ///< WEIGHTS_n
extern const GltfAccessorRule kIndices;         ///< primitive indices
extern const GltfAccessorRule kTime;            ///< animation sampler input
extern const GltfAccessorRule kVec3Output;      ///< translation and scale sampler output
extern const GltfAccessorRule kRotationOutput;  ///< rotation sampler output
extern const GltfAccessorRule kWeightsOutput;   ///< morph weights sampler output
extern const GltfAccessorRule kMatrix;          ///< inverse bind matrices
}  // namespace gltf_rules

/// Bytes of one component (1, 2 or 4), 0 for an unknown component type.
int gltf_component_size(int component_type);
/// Components of an accessor type (1 SCALAR .. 16 MAT4), 0 for an unknown type.
int gltf_type_components(int type);
/// Name of an accessor type in glTF JSON ("SCALAR" .. "MAT4").
std::string gltf_type_name(int type);
/// Bytes of one element, with the 4-byte column alignment of MAT2/MAT3 of small components.
size_t gltf_element_size(int component_type, int type);

/// Decoded accessor values, row-major count × components; normalized integers are mapped to
/// [0, 1] or [-1, 1] as glTF specifies (e.g. max(c / 127, -1) for a signed byte).
struct GltfAccessorValues {
  int count = 0;
  int components = 0;
  std::vector<double> values;
  double at(int element, int component) const {
    return values[size_t(element) * size_t(components) + size_t(component)];
  }
};

/// Largest accessor without bufferView (all zeros plus sparse values) that is decoded: 256 MiB of
/// elements, about 22 million VEC3 floats.
inline constexpr uint64_t kGltfMaxViewlessBytes = uint64_t(1) << 28;

/// Elements of accessor `index` as tightly packed bytes (element size as gltf_element_size),
/// sparse substitution applied; all zero where the accessor has no buffer view. Throws InputError
/// naming `accessors[index]` for an out-of-range index, bad component type or type, data outside
/// its buffer view (checked before anything is allocated by `count`), a byteStride smaller than
/// the element, or bad sparse indices.
std::vector<unsigned char> gltf_accessor_bytes(const GltfFile& file, int index);

/// Decodes accessor `index` after checking it against `rule`; `user` names the glTF element that
/// refers to it (e.g. "meshes[0].primitives[1].attributes.POSITION") for messages.
GltfAccessorValues read_gltf_accessor(const GltfFile& file, int index, const GltfAccessorRule& rule,
                                      const std::string& user);

}  // namespace sm
