#include "io/gltf/gltf_accessor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "core/coordinate_limit.hpp"

namespace sm {

namespace gltf_rules {
namespace {
constexpr int kByte = TINYGLTF_COMPONENT_TYPE_BYTE;
constexpr int kUByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kShort = TINYGLTF_COMPONENT_TYPE_SHORT;
constexpr int kUShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
}  // namespace

// Core glTF allows floats only for positions, normals and tangents; KHR_mesh_quantization adds
// (normalized) integers, which decode the same way.
const GltfAccessorRule kPosition{"POSITION",
                                 {TINYGLTF_TYPE_VEC3},
                                 {kFloat, kByte, kUByte, kShort, kUShort},
                                 {kByte, kUByte, kShort, kUShort}};
const GltfAccessorRule kNormal{"NORMAL", {TINYGLTF_TYPE_VEC3}, {kFloat}, {kByte, kShort}};
const GltfAccessorRule kTangent{"TANGENT", {TINYGLTF_TYPE_VEC4}, {kFloat}, {kByte, kShort}};
const GltfAccessorRule kJoints{"JOINTS", {TINYGLTF_TYPE_VEC4}, {kUByte, kUShort}, {}};
const GltfAccessorRule kWeights{"WEIGHTS", {TINYGLTF_TYPE_VEC4}, {kFloat}, {kUByte, kUShort}};
const GltfAccessorRule kIndices{"indices", {TINYGLTF_TYPE_SCALAR}, {kUByte, kUShort, kUInt}, {}};
const GltfAccessorRule kTime{"sampler input", {TINYGLTF_TYPE_SCALAR}, {kFloat}, {}};
const GltfAccessorRule kVec3Output{"translation/scale output", {TINYGLTF_TYPE_VEC3}, {kFloat}, {}};
const GltfAccessorRule kRotationOutput{
    "rotation output", {TINYGLTF_TYPE_VEC4}, {kFloat}, {kByte, kUByte, kShort, kUShort}};
const GltfAccessorRule kWeightsOutput{
    "weights output", {TINYGLTF_TYPE_SCALAR}, {kFloat}, {kByte, kUByte, kShort, kUShort}};
const GltfAccessorRule kMatrix{"inverseBindMatrices", {TINYGLTF_TYPE_MAT4}, {kFloat}, {}};
}  // namespace gltf_rules

int gltf_component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;  // INT (5124) and DOUBLE are not glTF 2.0 accessor component types
  }
}

int gltf_type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

std::string gltf_type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "";
  }
}

namespace {

int matrix_columns(int type) {
  return type == TINYGLTF_TYPE_MAT2   ? 2
         : type == TINYGLTF_TYPE_MAT3 ? 3
         : type == TINYGLTF_TYPE_MAT4 ? 4
                                      : 0;
}

/// Byte offset of component c inside an element (matrix columns start at 4-byte boundaries).
size_t component_offset(int component_type, int type, int c) {
  const size_t s = size_t(gltf_component_size(component_type));
  const int columns = matrix_columns(type);
  if (columns == 0) return size_t(c) * s;
  const size_t column_stride = (size_t(columns) * s + 3) / 4 * 4;
  return size_t(c / columns) * column_stride + size_t(c % columns) * s;
}

double decode_component(const unsigned char* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const int8_t v = int8_t(p[0]);
      return normalized ? std::max(v / 127.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : double(p[0]);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : double(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : double(v);
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return double(v);
    }
  }
}

std::string name_of(int index) {
  return "accessors[" + std::to_string(index) + "]";
}

/// Checks that [offset, offset + size) lies in bufferViews[view]; returns a pointer to it.
const unsigned char* view_range(const GltfFile& file, int accessor, int view, uint64_t offset,
                                uint64_t size, const char* what) {
  const tinygltf::Model& m = file.model;
  if (view < 0 || size_t(view) >= m.bufferViews.size()) {
    throw_gltf_error(file.path, name_of(accessor),
                     std::string(what) + " bufferView " + std::to_string(view) + " does not exist");
  }
  const tinygltf::BufferView& v = m.bufferViews[size_t(view)];
  if (offset > v.byteLength || size > v.byteLength - offset) {  // no overflow on huge offsets
    throw_gltf_error(file.path, name_of(accessor),
                     std::string(what) + " needs bytes " + std::to_string(offset) + ".." +
                         std::to_string(offset + size) + " of bufferViews[" + std::to_string(view) +
                         "], which has " + std::to_string(v.byteLength));
  }
  return m.buffers[size_t(v.buffer)].data.data() + v.byteOffset + offset;
}

// Substitutes the sparse values of accessor `index` (element bytes each) into `out`.
void apply_sparse(const GltfFile& file, int index, size_t element,
                  std::vector<unsigned char>& out) {
  const tinygltf::Accessor& a = file.model.accessors[size_t(index)];
  const auto count = uint64_t(std::max(a.sparse.count, 0));
  if (a.sparse.count < 1 || count > a.count) {
    throw_gltf_error(file.path, name_of(index) + ".sparse",
                     "count " + std::to_string(a.sparse.count) + " is not in [1, " +
                         std::to_string(a.count) + "]");
  }
  const int index_type = a.sparse.indices.componentType;
  const int isize = gltf_component_size(index_type);
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    throw_gltf_error(file.path, name_of(index) + ".sparse.indices",
                     "componentType " + std::to_string(index_type) + " is not an unsigned int");
  }
  const unsigned char* ids = view_range(file, index, a.sparse.indices.bufferView,
                                        uint64_t(std::max(a.sparse.indices.byteOffset, 0)),
                                        count * size_t(isize), "sparse.indices");
  const unsigned char* values = view_range(file, index, a.sparse.values.bufferView,
                                           uint64_t(std::max(a.sparse.values.byteOffset, 0)),
                                           count * element, "sparse.values");
  double previous = -1;
  for (size_t k = 0; k < count; ++k) {
    const double id = decode_component(ids + k * size_t(isize), index_type, false);
    if (id <= previous || id >= double(a.count)) {
      throw_gltf_error(file.path, name_of(index) + ".sparse.indices",
                       "index " + std::to_string(uint64_t(id)) + " at position " +
                           std::to_string(k) + " is out of range or not increasing");
    }
    previous = id;
    std::memcpy(out.data() + size_t(id) * element, values + k * element, element);
  }
}

}  // namespace

size_t gltf_element_size(int component_type, int type) {
  const int n = gltf_type_components(type);
  if (n == 0 || gltf_component_size(component_type) == 0) return 0;
  const int columns = matrix_columns(type);
  if (columns == 0) return size_t(n) * size_t(gltf_component_size(component_type));
  return component_offset(component_type, type, n - columns) +
         (size_t(columns) * size_t(gltf_component_size(component_type)) + 3) / 4 * 4;
}

std::vector<unsigned char> gltf_accessor_bytes(const GltfFile& file, int index) {
  const tinygltf::Model& m = file.model;
  if (index < 0 || size_t(index) >= m.accessors.size()) {
    throw_gltf_error(
        file.path, name_of(index),
        "does not exist (the file has " + std::to_string(m.accessors.size()) + " accessors)");
  }
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  const size_t element = gltf_element_size(a.componentType, a.type);
  if (element == 0) {
    throw_gltf_error(file.path, name_of(index),
                     "componentType " + std::to_string(a.componentType) + " or type " +
                         std::to_string(a.type) + " is not valid in glTF 2.0");
  }
  // The count comes from the file: check it against the bytes that hold the data before
  // allocating anything by it. A view-less accessor is all zeros plus its sparse values: cap its
  // size (kGltfMaxViewlessBytes) so that a corrupt count cannot ask for an absurd allocation.
  if (a.count > (uint64_t(1) << 31) ||
      (a.bufferView < 0 && uint64_t(a.count) * element > kGltfMaxViewlessBytes)) {
    throw_gltf_error(file.path, name_of(index),
                     "count " + std::to_string(a.count) +
                         " is too large for an accessor without bufferView (at most " +
                         std::to_string(kGltfMaxViewlessBytes / element) + " elements)");
  }
  const unsigned char* src = nullptr;
  size_t stride = element;
  if (a.bufferView >= 0 && a.count > 0) {
    const size_t view_stride = size_t(a.bufferView) < m.bufferViews.size()
                                   ? m.bufferViews[size_t(a.bufferView)].byteStride
                                   : 0;
    if (view_stride != 0 && view_stride < element) {
      throw_gltf_error(file.path, name_of(index),
                       "bufferViews[" + std::to_string(a.bufferView) + "].byteStride " +
                           std::to_string(view_stride) + " is smaller than its element (" +
                           std::to_string(element) + " bytes): elements would overlap");
    }
    if (view_stride != 0) stride = view_stride;
    src = view_range(file, index, a.bufferView, a.byteOffset,
                     uint64_t(stride) * (a.count - 1) + element, "data");
  }
  std::vector<unsigned char> out(a.count * element, 0);
  if (src) {
    for (size_t e = 0; e < a.count; ++e) {
      std::memcpy(out.data() + e * element, src + e * stride, element);
    }
  }
  if (a.sparse.isSparse) apply_sparse(file, index, element, out);
  return out;
}

GltfAccessorValues read_gltf_accessor(const GltfFile& file, int index, const GltfAccessorRule& rule,
                                      const std::string& user) {
  const tinygltf::Model& m = file.model;
  if (index < 0 || size_t(index) >= m.accessors.size()) {
    throw_gltf_error(file.path, user,
                     "accessor " + std::to_string(index) + " does not exist (the file has " +
                         std::to_string(m.accessors.size()) + " accessors)");
  }
  const tinygltf::Accessor& a = m.accessors[size_t(index)];
  const auto has = [](const std::vector<int>& list, int v) {
    return std::find(list.begin(), list.end(), v) != list.end();
  };
  const bool type_ok = has(rule.types, a.type);
  const bool component_ok = a.normalized ? has(rule.normalized_ints, a.componentType)
                                         : has(rule.float_or_int, a.componentType);
  if (!type_ok || !component_ok) {
    throw_gltf_error(file.path, name_of(index),
                     "type " + std::to_string(a.type) + ", componentType " +
                         std::to_string(a.componentType) + (a.normalized ? " (normalized)" : "") +
                         " is not allowed for " + rule.role + " (used by " + user + ")");
  }
  const std::vector<unsigned char> bytes = gltf_accessor_bytes(file, index);
  GltfAccessorValues out;
  out.count = int(a.count);
  out.components = gltf_type_components(a.type);
  out.values.resize(a.count * size_t(out.components));
  const size_t element = gltf_element_size(a.componentType, a.type);
  for (size_t e = 0; e < a.count; ++e) {
    for (int c = 0; c < out.components; ++c) {
      const double v = decode_component(
          bytes.data() + e * element + component_offset(a.componentType, a.type, c),
          a.componentType, a.normalized);
      if (!std::isfinite(v)) {
        throw_gltf_error(file.path, name_of(index),
                         "element " + std::to_string(e) + " is not a finite number");
      }
      if (&rule == &gltf_rules::kPosition && std::abs(v) > kMaxCoordinate) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", v);
        throw_gltf_error(file.path, name_of(index),
                         "element " + std::to_string(e) + ": POSITION value " + text +
                             " is too large (more than 1e18 in magnitude: the geometry would "
                             "overflow)");
      }
      out.values[e * size_t(out.components) + size_t(c)] = v;
    }
  }
  return out;
}

}  // namespace sm
