// The glTF trust boundary: external resources stay inside the model's folder (percent-decoded,
// no absolute path, no escape lexically or through a symlink, regular files only), JSON depth and
// accessor counts are checked before anything recurses or allocates by them, byte strides and
// coordinates that make no sense are input errors.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_file.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/gltf/gltf_resource.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/gltf_models.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

namespace fs = std::filesystem;
using Catch::Contains;
using nlohmann::json;
using test::error_of;
using test::TempDir;

GltfSequence load_untrusted(const fs::path& file) {
  return load_gltf_sequence({file, "", "", std::nullopt});
}

/// The node-animated triangle as `<dir>/model/t.gltf` with its buffer in `<dir>/model/t.bin`;
/// `edit` changes the JSON before it is written back. Returns the .gltf path.
template <class Edit>
fs::path model_with(const TempDir& dir, Edit edit) {
  fs::create_directories(dir / "model");
  const fs::path file = dir / "model/t.gltf";
  test::node_animated_triangle().save(file, false);
  json doc = json::parse(read_file(file));
  edit(doc);
  write_file_atomic(file, doc.dump());
  return file;
}

fs::path model_with_uri(const TempDir& dir, const std::string& uri) {
  return model_with(dir, [&](json& doc) { doc["buffers"][0]["uri"] = uri; });
}

TEST_CASE("glTF: a buffer uri escaping the model's folder is refused, naming element and uri") {
  TempDir dir("gltf_escape");
  const fs::path file = model_with_uri(dir, "../t.bin");
  fs::copy_file(dir / "model/t.bin", dir / "t.bin");  // the file exists: it is still refused
  const std::string before = read_file(file);
  CHECK_THROWS_AS(load_gltf_file(file), InputError);
  CHECK(error_of([&] { load_gltf_file(file); }) ==
        "'" + file.string() + "': buffers[0].uri '../t.bin': resolves outside the model's folder");
  // Encoded dots and slashes are decoded first; a detour inside the folder is fine lexically.
  write_file_atomic(file, json::parse(before).dump());
  json doc = json::parse(before);
  doc["buffers"][0]["uri"] = "%2E%2E%2Ft.bin";
  write_file_atomic(file, doc.dump());
  CHECK_THAT(error_of([&] { load_gltf_file(file); }),
             Contains("buffers[0].uri '%2E%2E%2Ft.bin': resolves outside the model's folder"));
  doc["buffers"][0]["uri"] = "sub/../../model/t.bin";
  write_file_atomic(file, doc.dump());
  CHECK_THAT(error_of([&] { load_gltf_file(file); }), Contains("resolves outside"));
  doc["buffers"][0]["uri"] = "./sub/../t.bin";
  fs::create_directories(dir / "model/sub");
  write_file_atomic(file, doc.dump());
  CHECK(load_untrusted(file).num_frames() > 1);
}

TEST_CASE("glTF: an absolute buffer uri to an existing file says why it is refused") {
  TempDir dir("gltf_absolute");
  const fs::path bin = fs::absolute(dir / "model/t.bin");
  const fs::path file = model_with(dir, [](json&) {});
  json doc = json::parse(read_file(file));
  doc["buffers"][0]["uri"] = bin.string();
  write_file_atomic(file, doc.dump());
  const std::string message = error_of<InputError>([&] { load_gltf_file(file); });
  CHECK_THAT(message, Contains("buffers[0].uri '" + bin.string() +
                               "': is an absolute path; only files inside the model's folder"));
  CHECK_THAT(message, !Contains("not found"));
  doc["buffers"][0]["uri"] = "file://" + bin.string();
  write_file_atomic(file, doc.dump());
  CHECK_THAT(error_of<InputError>([&] { load_gltf_file(file); }), Contains("has a URI scheme"));
}

TEST_CASE("glTF: a symlink out of the model's folder and a FIFO are refused") {
  TempDir dir("gltf_symlink");
  const fs::path file = model_with_uri(dir, "link.bin");
  fs::copy_file(dir / "model/t.bin", dir / "outside.bin");
  fs::create_symlink("../outside.bin", dir / "model/link.bin");
  CHECK_THAT(error_of<InputError>([&] { load_gltf_file(file); }),
             Contains("buffers[0].uri 'link.bin': resolves outside the model's folder (through a "
                      "symlink"));
  // A symlink that stays inside is read.
  fs::remove(dir / "model/link.bin");
  fs::create_symlink("t.bin", dir / "model/link.bin");
  CHECK(load_untrusted(file).num_frames() > 1);
  // A FIFO must not block the load: it is refused by its kind.
  fs::remove(dir / "model/link.bin");
  REQUIRE(::mkfifo((dir / "model/link.bin").c_str(), 0600) == 0);
  CHECK(error_of<InputError>([&] { load_gltf_file(file); }) ==
        "'" + file.string() + "': buffers[0].uri 'link.bin': names a FIFO, not a regular file");
  fs::remove(dir / "model/link.bin");
  fs::create_directories(dir / "model/link.bin");
  CHECK_THAT(error_of<InputError>([&] { load_gltf_file(file); }),
             Contains("'link.bin': names a folder, not a regular file"));
}

TEST_CASE("glTF: percent-encoded names are decoded once, '+' stays a plus, and are hashed") {
  TempDir dir("gltf_percent");
  for (const std::string name : {"my model.bin", "a+b.bin", "100%.bin"}) {
    std::string uri = name;
    if (name == "my model.bin") uri = "my%20model.bin";
    if (name == "100%.bin") uri = "100%25.bin";
    const fs::path file = model_with_uri(dir, uri);
    fs::rename(dir / "model/t.bin", dir / "model" / name);
    const GltfFile loaded = load_gltf_file(file);
    REQUIRE(loaded.resources.size() == 1);
    CHECK(loaded.resources[0] == dir / "model" / name);
    CHECK(load_untrusted(file).num_frames() > 1);
    fs::remove(dir / "model" / name);
  }
  const fs::path file = model_with_uri(dir, "bad%2.bin");
  CHECK_THAT(error_of<InputError>([&] { load_gltf_file(file); }),
             Contains("buffers[0].uri 'bad%2.bin': malformed percent-encoding"));
}

TEST_CASE("glTF: an image uri outside the model's folder is refused") {
  TempDir dir("gltf_image");
  const fs::path file = model_with(dir, [](json& doc) {
    doc["images"] = json::array({{{"uri", "../../secret.png"}}});
  });
  CHECK(error_of<InputError>([&] { load_gltf_file(file); }) ==
        "'" + file.string() +
            "': images[0].uri '../../secret.png': resolves outside the model's folder");
}

TEST_CASE("glTF: JSON nested 20,000 levels deep is refused before any parser recurses") {
  TempDir dir("gltf_deep");
  const fs::path file = model_with(dir, [](json& doc) { doc["extras"] = json::array(); });
  std::string text = read_file(file);
  const size_t at = text.find("\"extras\":[]");
  REQUIRE(at != std::string::npos);
  text.replace(at, 11, "\"extras\":" + std::string(20000, '[') + std::string(20000, ']'));
  write_file_atomic(file, text);
  CHECK_THAT(error_of<InputError>([&] { load_gltf_file(file); }),
             Contains("': JSON: nests deeper than 128 levels (at byte "));
  // Brackets inside strings do not count.
  text = read_file(file);
  text.replace(text.find("\"extras\":"), 9 + 40000,
               "\"extras\":\"" + std::string(1000, '[') + "\\\"\"");
  write_file_atomic(file, text);
  CHECK(load_untrusted(file).num_frames() > 1);
}

TEST_CASE("glTF: an accessor count beyond its buffer view is refused before allocating by it") {
  TempDir dir("gltf_count");
  for (const uint64_t count : {uint64_t(400000000), uint64_t(2147483647)}) {
    const fs::path file =
        model_with(dir, [&](json& doc) { doc["accessors"][0]["count"] = count; });
    const std::string message = error_of<InputError>([&] { load_untrusted(file); });
    CHECK_THAT(message, Contains("accessors[0]: data needs bytes 0.."));
    CHECK_THAT(message, Contains("of bufferViews[0], which has "));
  }
}

TEST_CASE("glTF: a byteStride smaller than the element is refused") {
  TempDir dir("gltf_stride");
  const fs::path file = model_with(dir, [&](json& doc) {
    const size_t view = doc["accessors"][0]["bufferView"].get<size_t>();
    doc["bufferViews"][view]["byteStride"] = 4;
  });
  CHECK_THAT(error_of<InputError>([&] { load_untrusted(file); }),
             Contains("accessors[0]: bufferViews[0].byteStride 4 is smaller than its element (12 "
                      "bytes): elements would overlap"));
}

TEST_CASE("glTF: a finite POSITION too large for the geometry names the element and value") {
  TempDir dir("gltf_huge");
  test::ModelBuilder b = test::node_animated_triangle();
  const int positions = b.m.meshes[0].primitives[0].attributes.at("POSITION");
  const tinygltf::Accessor& a = b.m.accessors[size_t(positions)];
  const tinygltf::BufferView& v = b.m.bufferViews[size_t(a.bufferView)];
  const float huge = 1e30f;
  std::memcpy(b.m.buffers[0].data.data() + v.byteOffset + 4, &huge, sizeof huge);  // vertex 0, y
  fs::create_directories(dir / "model");
  b.save(dir / "model/t.glb", true);
  CHECK_THAT(error_of<InputError>([&] { load_untrusted(dir / "model/t.glb"); }),
             Contains("accessors[" + std::to_string(positions) +
                      "]: element 0: POSITION value 1e+30 is too large (more than 1e18 in "
                      "magnitude"));
}

TEST_CASE("glTF: more than 100,000 sampled frames are refused before they are planned") {
  TempDir dir("gltf_frames");
  const fs::path file = model_with(dir, [](json&) {});  // keyframes over t in [0, 2]
  GltfInputOptions options{file, "", "", 50000.0};       // 100,001 frames
  CHECK_THAT(error_of<ConfigError>([&] { load_gltf_sequence(options); }),
             Contains("input.fps: ") && Contains(" exceed 100000 frames"));
  options.fps = 49999.0;  // 99,999 frames: accepted
  CHECK(load_gltf_sequence(options).num_frames() == 99999);
}

}  // namespace
}  // namespace sm
