#include "io/gltf/gltf_file.hpp"

#include <cctype>
#include <cstdint>
#include <cstring>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_resource.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
using nlohmann::json;

bool gltf_extension_is_kept(const std::string& name) {
  return name == "KHR_mesh_quantization" || name == "KHR_texture_transform" ||
         name == "KHR_texture_basisu" || name == "EXT_texture_webp" ||
         name.rfind("KHR_materials_", 0) == 0;
}

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

uint32_t read_u32(const std::string& bytes, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

struct GlbLayout {
  size_t json_offset = 0;
  size_t json_size = 0;
  bool has_bin = false;
};

/// Checks the GLB header and chunk table against the file size (GLB 2.0, §4.4 of the spec).
GlbLayout check_glb(const fs::path& file, const std::string& bytes) {
  const size_t size = bytes.size();
  if (size < 20) {
    throw_gltf_error(file, "GLB header",
                     "truncated: " + std::to_string(size) + " bytes, a GLB needs at least 20");
  }
  const uint32_t version = read_u32(bytes, 4);
  if (version != 2) {
    throw_gltf_error(file, "GLB header", "version " + std::to_string(version) + ", expected 2");
  }
  const uint64_t length = read_u32(bytes, 8);
  if (length > size) {
    throw_gltf_error(file, "GLB header",
                     "truncated: the header declares " + std::to_string(length) +
                         " bytes but the file has " + std::to_string(size));
  }
  GlbLayout layout;
  layout.json_size = read_u32(bytes, 12);
  layout.json_offset = 20;
  if (read_u32(bytes, 16) != kChunkJson) throw_gltf_error(file, "GLB chunk 0", "not a JSON chunk");
  if (layout.json_offset + layout.json_size > length) {
    throw_gltf_error(file, "GLB JSON chunk",
                     "truncated: " + std::to_string(layout.json_size) + " bytes declared, " +
                         std::to_string(length - layout.json_offset) + " present");
  }
  const uint64_t bin_header = layout.json_offset + layout.json_size;
  if (bin_header < length) {
    if (bin_header + 8 > length) throw_gltf_error(file, "GLB BIN chunk", "truncated chunk header");
    const uint64_t bin_size = read_u32(bytes, bin_header);
    if (read_u32(bytes, bin_header + 4) != kChunkBin) {
      throw_gltf_error(file, "GLB chunk 1", "not a BIN chunk");
    }
    if (bin_header + 8 + bin_size > length) {
      throw_gltf_error(file, "GLB BIN chunk",
                       "truncated: " + std::to_string(bin_size) + " bytes declared, " +
                           std::to_string(length - bin_header - 8) + " present");
    }
    layout.has_bin = true;
  }
  return layout;
}

/// Refuses JSON text that nests deeper than kGltfMaxJsonDepth, before any parser recurses into it
/// (tinygltf copies `extras` recursively: 20,000 nested arrays overflow the stack).
void check_json_depth(const fs::path& file, const char* text, size_t size) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') ++i;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kGltfMaxJsonDepth) {
        throw_gltf_error(file, "JSON",
                         "nests deeper than " + std::to_string(kGltfMaxJsonDepth) +
                             " levels (at byte " + std::to_string(i) + ")");
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

bool is_data_uri(const std::string& uri) {
  return uri.rfind("data:", 0) == 0;
}

const json& array_member(const json& doc, const char* key) {
  static const json empty = json::array();
  const auto it = doc.find(key);
  return it != doc.end() && it->is_array() ? *it : empty;
}

/// Checks what tinygltf would otherwise report vaguely or read out of bounds: buffer and image
/// files that are missing or outside the model's folder (io/gltf/gltf_resource.hpp), a GLB buffer
/// without BIN chunk, image buffer views outside their buffer. Allows `resources` to read the
/// files and lists them, buffers first, in `files`.
void check_resources(const fs::path& file, const json& doc, bool is_glb, bool has_bin,
                     GltfResourceFiles& resources, std::vector<fs::path>& files) {
  const auto external = [&](const std::string& element, const std::string& uri, const char* what) {
    files.push_back(resolve_gltf_resource(file, element, uri, what));
    resources.add(uri, files.back());
  };
  const json& buffers = array_member(doc, "buffers");
  for (size_t i = 0; i < buffers.size(); ++i) {
    const std::string element = "buffers[" + std::to_string(i) + "]";
    const json& b = buffers[i];
    if (!b.is_object()) throw_gltf_error(file, element, "not an object");
    const auto uri = b.find("uri");
    if (uri == b.end()) {
      if (!is_glb)
        throw_gltf_error(file, element, "no uri (only a GLB's first buffer may omit it)");
      if (i != 0) throw_gltf_error(file, element, "no uri (only the first buffer may omit it)");
      if (!has_bin)
        throw_gltf_error(file, element, "refers to the GLB BIN chunk, which is missing");
      continue;
    }
    if (!uri->is_string()) throw_gltf_error(file, element, "uri is not a string");
    const std::string u = uri->get<std::string>();
    if (!is_data_uri(u)) external(element, u, "buffer");
  }
  const json& views = array_member(doc, "bufferViews");
  const json& images = array_member(doc, "images");
  for (size_t i = 0; i < images.size(); ++i) {
    const std::string element = "images[" + std::to_string(i) + "]";
    const json& image = images[i];
    if (!image.is_object()) throw_gltf_error(file, element, "not an object");
    const auto uri = image.find("uri");
    if (uri != image.end() && uri->is_string()) {
      const std::string u = uri->get<std::string>();
      if (!is_data_uri(u)) external(element, u, "image");
      continue;
    }
    const auto view = image.find("bufferView");
    if (view == image.end() || !view->is_number_unsigned() || *view >= views.size()) {
      throw_gltf_error(file, element, "needs a uri or a valid bufferView");
    }
    const json& v = views[view->get<size_t>()];
    const uint64_t offset = v.value("byteOffset", uint64_t(0));
    const uint64_t length = v.value("byteLength", uint64_t(0));
    const uint64_t buffer = v.value("buffer", uint64_t(buffers.size()));
    if (buffer >= buffers.size() ||
        offset + length > buffers[buffer].value("byteLength", uint64_t(0))) {
      throw_gltf_error(
          file, element,
          "bufferViews[" + std::to_string(view->get<size_t>()) + "] lies outside its buffer");
    }
  }
}

void check_extensions(const fs::path& file, const json& doc) {
  const json& required = array_member(doc, "extensionsRequired");
  for (const json& e : required) {
    const std::string name = e.is_string() ? e.get<std::string>() : e.dump();
    if (!gltf_extension_is_kept(name)) {
      throw_gltf_error(file, "extensionsRequired", "extension " + name + " is not supported");
    }
  }
}

void check_buffer_views(const fs::path& file, const tinygltf::Model& model) {
  for (size_t i = 0; i < model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& v = model.bufferViews[i];
    const std::string element = "bufferViews[" + std::to_string(i) + "]";
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size()) {
      throw_gltf_error(file, element, "buffer " + std::to_string(v.buffer) + " does not exist");
    }
    const size_t size = model.buffers[size_t(v.buffer)].data.size();
    if (v.byteOffset > size || v.byteLength > size - v.byteOffset) {
      throw_gltf_error(file, element,
                       "bytes " + std::to_string(v.byteOffset) + ".." +
                           std::to_string(v.byteOffset + v.byteLength) + " exceed buffers[" +
                           std::to_string(v.buffer) + "] (" + std::to_string(size) + " bytes)");
    }
    if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252 || v.byteStride % 4 != 0)) {
      throw_gltf_error(
          file, element,
          "byteStride " + std::to_string(v.byteStride) + " is not a multiple of 4 in [4, 252]");
    }
  }
}

/// Keeps images encoded: the writer copies their bytes, nothing here needs pixels.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

}  // namespace

GltfFile load_gltf_file(const fs::path& path) {
  return parse_gltf_file(path, read_file(path));
}

GltfFile parse_gltf_file(const fs::path& path, const std::string& bytes) {
  GltfFile out;
  out.path = path;
  const bool is_glb = bytes.size() >= 4 && read_u32(bytes, 0) == kGlbMagic;
  GlbLayout layout;
  if (is_glb) layout = check_glb(path, bytes);
  const char* json_text = is_glb ? bytes.data() + layout.json_offset : bytes.data();
  const size_t json_size = is_glb ? layout.json_size : bytes.size();
  check_json_depth(path, json_text, json_size);
  try {
    out.json = json::parse(json_text, json_text + json_size);
  } catch (const json::exception& e) {
    throw_gltf_error(path, "JSON", std::string("not valid JSON: ") + e.what());
  }
  if (!out.json.is_object()) throw_gltf_error(path, "JSON", "the document is not an object");
  const std::string base_dir = path.has_parent_path() ? path.parent_path().string() : ".";
  GltfResourceFiles resources(base_dir);
  try {
    check_extensions(path, out.json);
    check_resources(path, out.json, is_glb, layout.has_bin, resources, out.resources);
  } catch (const json::exception& e) {  // a member of the wrong JSON type
    throw_gltf_error(path, "JSON", std::string("unexpected value: ") + e.what());
  }

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  loader.SetFsCallbacks(resources.callbacks());  // reads the checked resources, nothing else
  std::string err, warn;
  const bool ok =
      is_glb ? loader.LoadBinaryFromMemory(&out.model, &err, &warn,
                                           reinterpret_cast<const unsigned char*>(bytes.data()),
                                           static_cast<unsigned>(bytes.size()), base_dir)
             : loader.LoadASCIIFromString(&out.model, &err, &warn, bytes.data(),
                                          static_cast<unsigned>(bytes.size()), base_dir);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw_gltf_error(path, "glTF", "tinygltf could not load it: " + err);
  }
  for (size_t i = 0; i < out.model.images.size(); ++i) {
    if (out.model.images[i].image.empty()) {
      throw_gltf_error(path, "images[" + std::to_string(i) + "]", "no image data could be read");
    }
  }
  check_buffer_views(path, out.model);
  return out;
}

}  // namespace sm
