#pragma once
/// Assembling a GLB file: a JSON document plus one binary buffer of 4-byte aligned buffer views,
/// with helpers for the accessors a writer adds to it.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sm {

class GlbBuilder {
 public:
  /// The JSON document being built; bufferViews, accessors and buffers are filled by this class.
  nlohmann::json& document() { return doc_; }

  /// Reserves room for `bytes` of binary data (avoids regrowing a large buffer).
  void reserve(size_t bytes) { bin_.reserve(bytes); }
  size_t binary_size() const { return bin_.size(); }

  /// Appends `size` bytes as a new buffer view (target 0 = none, stride 0 = none); returns its
  /// index.
  int add_view(const void* data, size_t size, int target = 0, int stride = 0);

  /// Adds an accessor of `type` (TINYGLTF_TYPE_*) over buffer view `view`; `min`/`max` are
  /// written when not empty.
  int add_accessor(int view, size_t byte_offset, int component_type, int type, size_t count,
                   bool normalized, const std::vector<double>& min = {},
                   const std::vector<double>& max = {});

  /// Adds float data (count × components of `type`) in a new buffer view; `bounds` adds min and
  /// max computed from the stored float values.
  int add_floats(const std::vector<float>& values, int type, int target, bool bounds);

  /// The GLB bytes (header, JSON chunk padded with spaces, BIN chunk padded with zeros). Leaves
  /// the builder empty.
  std::string finish();

 private:
  nlohmann::json doc_ = nlohmann::json::object();
  std::string bin_;
};

}  // namespace sm
