#include "support/gltf_models.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace sm::test {
namespace fs = std::filesystem;

namespace {

// A 1×1 RGB PNG (one orange pixel).
const std::vector<unsigned char> kPng = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
    0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
    0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78,
    0x9c, 0x63, 0xf8, 0xdf, 0xc0, 0x00, 0x00, 0x04, 0x01, 0x01, 0x80, 0xc5, 0x2a, 0x18,
    0x5d, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

std::vector<double> translation_matrix(double x, double y, double z) {
  return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1};  // column-major
}

}  // namespace

ModelBuilder::ModelBuilder() {
  m.asset.version = "2.0";
  m.asset.generator = "seqmassage tests";
  m.buffers.emplace_back();
  m.scenes.emplace_back();
  m.defaultScene = 0;
}

int ModelBuilder::view(const void* data, size_t bytes, int target, int stride) {
  std::vector<unsigned char>& buffer = m.buffers[0].data;
  buffer.resize((buffer.size() + 3) / 4 * 4, 0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = buffer.size();
  v.byteLength = bytes;
  v.target = target;
  v.byteStride = size_t(stride);
  const auto* p = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), p, p + bytes);
  m.bufferViews.push_back(v);
  return int(m.bufferViews.size()) - 1;
}

int ModelBuilder::accessor(int view, int component_type, int type, size_t count, bool normalized,
                           size_t byte_offset) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = component_type;
  a.type = type;
  a.count = count;
  a.normalized = normalized;
  a.byteOffset = byte_offset;
  m.accessors.push_back(a);
  return int(m.accessors.size()) - 1;
}

int ModelBuilder::floats(const std::vector<float>& values, int type, int target) {
  const size_t n = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
  const int v = view(values.data(), values.size() * sizeof(float), target);
  const int a = accessor(v, TINYGLTF_COMPONENT_TYPE_FLOAT, type, values.size() / n);
  if (type == TINYGLTF_TYPE_SCALAR || type == TINYGLTF_TYPE_VEC3) {  // inputs and positions
    std::vector<double>& lo = m.accessors[size_t(a)].minValues;
    std::vector<double>& hi = m.accessors[size_t(a)].maxValues;
    lo.assign(n, INFINITY);
    hi.assign(n, -INFINITY);
    for (size_t i = 0; i < values.size(); ++i) {
      lo[i % n] = std::min(lo[i % n], double(values[i]));
      hi[i % n] = std::max(hi[i % n], double(values[i]));
    }
  }
  return a;
}

int ModelBuilder::ubytes(const std::vector<uint8_t>& values, int type, bool normalized,
                         int target) {
  const size_t n = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
  return accessor(view(values.data(), values.size(), target), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                  type, values.size() / n, normalized);
}

int ModelBuilder::ushorts(const std::vector<uint16_t>& values, int type, bool normalized,
                          int target) {
  const size_t n = size_t(tinygltf::GetNumComponentsInType(uint32_t(type)));
  return accessor(view(values.data(), values.size() * 2, target),
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, type, values.size() / n, normalized);
}

int ModelBuilder::node(const std::string& name) {
  m.nodes.emplace_back();
  m.nodes.back().name = name;
  return int(m.nodes.size()) - 1;
}

void ModelBuilder::channel(int node, const std::string& path, const std::vector<float>& times,
                           const std::vector<float>& values, const std::string& interpolation) {
  if (m.animations.empty()) {
    m.animations.emplace_back();
    m.animations[0].name = "take";
  }
  tinygltf::Animation& anim = m.animations[0];
  tinygltf::AnimationSampler s;
  s.input = floats(times, TINYGLTF_TYPE_SCALAR);
  const int type = path == "rotation"  ? TINYGLTF_TYPE_VEC4
                   : path == "weights" ? TINYGLTF_TYPE_SCALAR
                                       : TINYGLTF_TYPE_VEC3;
  s.output = floats(values, type);
  m.accessors[size_t(s.output)].minValues.clear();
  m.accessors[size_t(s.output)].maxValues.clear();
  s.interpolation = interpolation;
  anim.samplers.push_back(s);
  tinygltf::AnimationChannel c;
  c.sampler = int(anim.samplers.size()) - 1;
  c.target_node = node;
  c.target_path = path;
  anim.channels.push_back(c);
}

void ModelBuilder::save(const fs::path& file, bool binary) const {
  tinygltf::Model copy = m;
  if (!binary) copy.buffers[0].uri = file.stem().string() + ".bin";
  if (copy.scenes[0].nodes.empty()) {  // tinygltf would write an empty scene as null
    copy.scenes.clear();
    copy.defaultScene = -1;
  }
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&copy, file.string(), false, binary, true, binary)) {
    throw std::runtime_error("tinygltf could not write " + file.string());
  }
}

ModelBuilder morph_quad(const MorphQuadOptions& options) {
  ModelBuilder b;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = b.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3,
                                         TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["NORMAL"] = b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, TINYGLTF_TYPE_VEC3,
                                       TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["TANGENT"] = b.floats({1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1},
                                        TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.indices = b.ushorts({0, 1, 2, 0, 2, 3}, TINYGLTF_TYPE_SCALAR, false,
                           TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.targets.push_back(
      {{"POSITION", b.floats({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, TINYGLTF_TYPE_VEC3,
                             TINYGLTF_TARGET_ARRAY_BUFFER)}});
  if (options.sparse_target) {
    const uint8_t id = 3;
    const std::vector<float> delta = {0, 0, 2};
    tinygltf::Accessor a;
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = 4;
    a.minValues = {0, 0, 0};
    a.maxValues = {0, 0, 2};
    a.sparse.isSparse = true;
    a.sparse.count = 1;
    a.sparse.indices.bufferView = b.view(&id, 1);
    a.sparse.indices.byteOffset = 0;
    a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    a.sparse.values.bufferView = b.view(delta.data(), 12);
    a.sparse.values.byteOffset = 0;
    b.m.accessors.push_back(a);
    prim.targets.push_back({{"POSITION", int(b.m.accessors.size()) - 1}});
  } else {
    prim.targets.push_back(
        {{"POSITION", b.floats({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2}, TINYGLTF_TYPE_VEC3,
                               TINYGLTF_TARGET_ARRAY_BUFFER)}});
  }
  b.m.meshes.emplace_back();
  b.m.meshes[0].name = "quad";
  b.m.meshes[0].primitives.push_back(prim);
  b.m.meshes[0].weights = {0.5, 0};
  const int n = b.node("quad node");
  b.m.nodes[size_t(n)].mesh = 0;
  b.m.nodes[size_t(n)].translation = {1, 2, 3};
  b.m.scenes[0].nodes = {n};

  const std::vector<float> times = {0, 1, 2};
  const std::vector<float> keys = {0, 0, 1, 0.6f, 0, 1};
  std::vector<float> values = keys;
  if (options.interpolation == "CUBICSPLINE") {
    values.clear();
    for (size_t k = 0; k < 3; ++k)
      values.insert(values.end(), {0, 0, keys[2 * k], keys[2 * k + 1], 0, 0});
  }
  b.channel(n, "weights", times, values, options.interpolation);
  if (options.ubyte_weights) {  // replace the output by normalized bytes: 0.6 = 153 / 255
    std::vector<uint8_t> bytes;
    for (float v : values) bytes.push_back(uint8_t(std::lround(v * 255)));
    b.m.animations[0].samplers[0].output = b.ubytes(bytes, TINYGLTF_TYPE_SCALAR, true);
  }
  return b;
}

std::vector<double> morph_quad_weights(const MorphQuadOptions& options, double t) {
  const double keys[3][2] = {
      {0, 0}, {1, options.ubyte_weights ? 153 / 255.0 : double(0.6f)}, {0, 1}};
  if (t <= 0) return {keys[0][0], keys[0][1]};
  if (t >= 2) return {keys[2][0], keys[2][1]};
  const int k = t < 1 ? 0 : 1;
  const double u = t - k;
  double a = 1 - u, c = u;  // LINEAR
  if (options.interpolation == "STEP") a = 1, c = 0;
  if (options.interpolation == "CUBICSPLINE") a = 2 * u * u * u - 3 * u * u + 1, c = 1 - a;
  return {a * keys[k][0] + c * keys[k + 1][0], a * keys[k][1] + c * keys[k + 1][1]};
}

ModelBuilder node_animated_triangle() {
  ModelBuilder b;
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = b.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3);
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  b.m.meshes.emplace_back();
  b.m.meshes[0].primitives.push_back(prim);
  const int parent = b.node("parent");
  const int child = b.node("child");
  b.m.nodes[size_t(parent)].children = {child};
  b.m.nodes[size_t(child)].translation = {1, 0, 0};
  b.m.nodes[size_t(child)].mesh = 0;
  b.m.scenes[0].nodes = {parent};
  const float half = float(85.0 * M_PI / 180.0);
  b.channel(parent, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, std::sin(half), std::cos(half)},
            "LINEAR");
  b.channel(parent, "translation", {0, 2},
            {0, 0, 0, 0, 0, 0, 3, 0, 0, /* key 1: */ 0, 0, 0, 2, 0, 0, 0, 0, 0}, "CUBICSPLINE");
  b.channel(parent, "scale", {0, 1.5f}, {1, 1, 1, 2, 2, 2}, "STEP");
  return b;
}

ModelBuilder skinned_strip(bool two_sets) {
  ModelBuilder b;
  const double xs[6] = {0, 0.5, 1, 1, 1.5, 2};
  const double us[6] = {0, 0.25, 0.5, 0.6, 0.75, 1};
  std::vector<float> pos, uv, weights0, weights1f;
  std::vector<uint8_t> joints0, joints1, w0b, w1b;
  for (int c = 0; c < 6; ++c) {
    for (int row = 0; row < 2; ++row) {
      pos.insert(pos.end(), {float(xs[c]), float(row), 0});
      uv.insert(uv.end(), {float(us[c]), float(row)});
      const double w1 = xs[c] < 1 ? 0 : xs[c] > 1 ? 1 : 0.5;
      weights0.insert(weights0.end(), {float(1 - w1), float(w1), 0, 0});
      joints0.insert(joints0.end(), {0, 1, 0, 0});
      // Two sets, normalized bytes: the x = 1 column puts 0.6 on bone0 in set 0, 0.4 on bone1 in
      // set 1.
      const bool seam = xs[c] == 1;
      w0b.insert(w0b.end(),
                 {uint8_t(seam ? 153 : 255 * (1 - w1)), uint8_t(seam ? 0 : 255 * w1), 0, 0});
      joints1.insert(joints1.end(), {1, 0, 0, 0});
      w1b.insert(w1b.end(), {uint8_t(seam ? 102 : 0), 0, 0, 0});
    }
  }
  std::vector<uint16_t> tris;
  for (int c : {0, 1, 3, 4}) {
    const uint16_t a = uint16_t(2 * c), bb = uint16_t(2 * c + 2), cc = uint16_t(2 * c + 3),
                   d = uint16_t(2 * c + 1);
    tris.insert(tris.end(), {a, bb, cc, a, cc, d});
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = b.floats(pos, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["TEXCOORD_0"] = b.floats(uv, TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["JOINTS_0"] =
      b.ubytes(joints0, TINYGLTF_TYPE_VEC4, false, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (two_sets) {
    prim.attributes["WEIGHTS_0"] =
        b.ubytes(w0b, TINYGLTF_TYPE_VEC4, true, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["JOINTS_1"] =
        b.ubytes(joints1, TINYGLTF_TYPE_VEC4, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["WEIGHTS_1"] =
        b.ubytes(w1b, TINYGLTF_TYPE_VEC4, true, TINYGLTF_TARGET_ARRAY_BUFFER);
  } else {
    prim.attributes["WEIGHTS_0"] =
        b.floats(weights0, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  prim.indices = b.ushorts(tris, TINYGLTF_TYPE_SCALAR, false, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.material = 0;
  b.m.meshes.emplace_back();
  b.m.meshes[0].name = "strip";
  b.m.meshes[0].primitives.push_back(prim);

  const int armature = b.node("armature");
  const int bone0 = b.node("bone0");
  const int bone1 = b.node("bone1");
  const int mesh_node = b.node("strip");
  b.m.nodes[size_t(armature)].translation = {0, 0, 5};
  b.m.nodes[size_t(armature)].children = {bone0};
  b.m.nodes[size_t(bone0)].children = {bone1};
  b.m.nodes[size_t(bone1)].translation = {1, 0, 0};
  b.m.nodes[size_t(mesh_node)].mesh = 0;
  b.m.nodes[size_t(mesh_node)].skin = 0;
  b.m.nodes[size_t(mesh_node)].translation = {100, 0, 0};
  b.m.scenes[0].nodes = {armature, mesh_node};

  std::vector<float> ibm;
  for (const auto& mat : {translation_matrix(0, 0, -5), translation_matrix(-1, 0, -5)}) {
    for (double x : mat) ibm.push_back(float(x));
  }
  tinygltf::Skin skin;
  skin.joints = {bone0, bone1};
  skin.skeleton = bone0;
  skin.inverseBindMatrices = b.floats(ibm, TINYGLTF_TYPE_MAT4);
  b.m.skins.push_back(skin);
  const float s45 = float(std::sqrt(0.5));
  b.channel(bone1, "rotation", {0, 1}, {0, 0, 0, 1, 0, 0, s45, s45}, "LINEAR");

  tinygltf::Image image;
  image.bufferView = b.view(kPng.data(), kPng.size());
  image.mimeType = "image/png";
  image.name = "pixel";
  b.m.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  b.m.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  b.m.textures.push_back(texture);
  tinygltf::Material material;
  material.name = "pixel material";
  material.pbrMetallicRoughness.baseColorTexture.index = 0;
  material.pbrMetallicRoughness.metallicFactor = 0.25;
  b.m.materials.push_back(material);
  return b;
}

fs::path shared_gltf_dir() {
  return fs::path(SEQMASSAGE_SHARED_DATA_DIR) / "gltf";
}

bool have_shared_gltf() {
  if (fs::is_directory(shared_gltf_dir())) return true;
  WARN("skipped: the shared glTF models are not at " << shared_gltf_dir().string());
  return false;
}

// Measured with this reader; vertex counts agree with data/README.md §2 ("verts / uniq pos"),
// frame counts with its keyframe counts. Only the two minimal models are open: SimpleMorph is
// one triangle and SimpleSkin a strip of 8 triangles.
const SharedGltfModel kSharedGltfModels[10] = {
    {"skinned/CesiumMan/glTF-Binary/CesiumMan.glb", 3273, 2338, 4672, 48, 0},
    {"skinned/CesiumMan/glTF/CesiumMan.gltf", 3273, 2338, 4672, 48, 0},
    {"skinned/RiggedSimple/glTF-Binary/RiggedSimple.glb", 160, 96, 188, 50, 0},
    {"skinned/RiggedFigure/glTF-Binary/RiggedFigure.glb", 370, 130, 256, 2, 0},
    {"skinned/Fox/glTF-Binary/Fox.glb", 1728, 290, 576, 83, 0},
    {"skinned/SimpleSkin/glTF/SimpleSkin.gltf", 10, 10, 8, 12, 1},
    {"morph/AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb", 24, 8, 12, 127, 0},
    {"morph/AnimatedMorphSphere/glTF-Binary/AnimatedMorphSphere.glb", 1876, 482, 960, 217, 0},
    {"morph/MorphStressTest/glTF-Binary/MorphStressTest.glb", 1528, 1224, 2412, 281, 0},
    {"morph/SimpleMorph/glTF/SimpleMorph.gltf", 3, 3, 1, 5, 1},
};

const char* const kStaticGltfModels[3] = {
    "static/Box/glTF-Binary/Box.glb", "static/BoxTextured/glTF-Binary/BoxTextured.glb",
    "morph/MorphPrimitivesTest/glTF-Binary/MorphPrimitivesTest.glb"};

std::optional<int> validate_gltf(const fs::path& file, std::string& report) {
  if (std::system("command -v node >/dev/null 2>&1") != 0) {
    report = "node is not on PATH";
    return std::nullopt;
  }
  const fs::path script =
      fs::path(SEQMASSAGE_TEST_DIR).parent_path() / "tools" / "validate_gltf.js";
  fs::path out = file;
  out += ".validation.txt";
  const std::string command =
      "node '" + script.string() + "' '" + file.string() + "' > '" + out.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  report = text.str();
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code == 3) return std::nullopt;  // the gltf-validator package is not installed
  const size_t at = report.find(": errors ");
  if (at == std::string::npos) {
    report = "validator failed (exit " + std::to_string(code) + "): " + report;
    return -1;
  }
  return std::atoi(report.c_str() + at + 9);
}

void require_close(const Positions& got, const Positions& expected, double rel) {
  REQUIRE(got.rows() == expected.rows());
  const double scale = std::max(1.0, expected.cwiseAbs().maxCoeff());
  INFO("got\n" << got << "\nexpected\n" << expected);
  REQUIRE((got - expected).cwiseAbs().maxCoeff() <= rel * scale);
}

void require_valid_gltf(const fs::path& file) {
  std::string report;
  const std::optional<int> errors = validate_gltf(file, report);
  if (!errors) {
    while (!report.empty() && report.back() == '\n') report.pop_back();
    WARN("glTF-Validator not run: " << report);
    return;
  }
  INFO(report);
  REQUIRE(*errors == 0);
}

}  // namespace sm::test
