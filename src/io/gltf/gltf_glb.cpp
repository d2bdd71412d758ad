#include "io/gltf/gltf_glb.hpp"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "io/gltf/gltf_accessor.hpp"
#include "core/errors.hpp"

namespace sm {
using nlohmann::json;

int GlbBuilder::add_view(const void* data, size_t size, int target, int stride) {
  json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
  if (target != 0) view["target"] = target;
  if (stride != 0) view["byteStride"] = stride;
  bin_.append(static_cast<const char*>(data), size);
  bin_.append((4 - bin_.size() % 4) % 4, '\0');  // next view starts 4-byte aligned
  json& views = doc_["bufferViews"];
  views.push_back(std::move(view));
  return int(views.size()) - 1;
}

int GlbBuilder::add_accessor(int view, size_t byte_offset, int component_type, int type,
                             size_t count, bool normalized, const std::vector<double>& min,
                             const std::vector<double>& max) {
  json a = {{"bufferView", view},
            {"componentType", component_type},
            {"count", count},
            {"type", gltf_type_name(type)}};
  if (byte_offset != 0) a["byteOffset"] = byte_offset;
  if (normalized) a["normalized"] = true;
  if (!min.empty()) a["min"] = min;
  if (!max.empty()) a["max"] = max;
  json& accessors = doc_["accessors"];
  accessors.push_back(std::move(a));
  return int(accessors.size()) - 1;
}

int GlbBuilder::add_floats(const std::vector<float>& values, int type, int target, bool bounds) {
  const size_t components = size_t(gltf_type_components(type));
  const size_t count = values.size() / components;
  std::vector<double> min, max;
  if (bounds) {
    min.assign(components, std::numeric_limits<double>::infinity());
    max.assign(components, -std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < values.size(); ++i) {
      min[i % components] = std::min(min[i % components], double(values[i]));
      max[i % components] = std::max(max[i % components], double(values[i]));
    }
  }
  const int view = add_view(values.data(), values.size() * sizeof(float), target);
  return add_accessor(view, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, type, count, false, min, max);
}

namespace {

void append_u32(std::string& out, uint64_t v) {
  for (int i = 0; i < 4; ++i) out += char((v >> (8 * i)) & 0xFF);
}

}  // namespace

std::string GlbBuilder::finish() {
  if (!bin_.empty()) doc_["buffers"] = json::array({{{"byteLength", bin_.size()}}});
  std::string text = doc_.dump();
  text.append((4 - text.size() % 4) % 4, ' ');
  const uint64_t total = 12 + 8 + text.size() + (bin_.empty() ? 0 : 8 + bin_.size());
  if (total > std::numeric_limits<uint32_t>::max()) {
    throw IoError("the GLB would have " + std::to_string(total) +
                  " bytes; the format is limited to 4 GiB (write fewer frames or vertices)");
  }
  std::string glb;
  glb.reserve(size_t(total));
  glb += "glTF";
  append_u32(glb, 2);
  append_u32(glb, total);
  append_u32(glb, text.size());
  append_u32(glb, 0x4E4F534A);  // JSON
  glb += text;
  if (!bin_.empty()) {
    append_u32(glb, bin_.size());
    append_u32(glb, 0x004E4942);  // BIN
    glb += bin_;
  }
  bin_.clear();
  bin_.shrink_to_fit();
  doc_ = json::object();
  return glb;
}

}  // namespace sm
