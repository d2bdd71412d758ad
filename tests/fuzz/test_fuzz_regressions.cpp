// Replays the fuzz targets' seed corpus (tests/fuzz/corpus/<target>/) and every input a fuzzer
// found a problem with (tests/fuzz/regressions/<target>/) through the targets' entry functions,
// with the normal compiler, so that CI checks them without clang or libFuzzer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace fs = std::filesystem;

namespace {

using Target = void (*)(const uint8_t*, size_t);

std::vector<fs::path> inputs_of(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* kind : {"corpus", "regressions"}) {
    const fs::path dir = fs::path(SEQMASSAGE_FUZZ_DIR) / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().filename() != "README.md")
        files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Runs `target` over every input; returns how many there were.
size_t replay(const std::string& name, Target target) {
  const std::vector<fs::path> files = inputs_of(name);
  for (const fs::path& file : files) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    INFO(file.string());
    CHECK_NOTHROW(target(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  }
  return files.size();
}

}  // namespace

TEST_CASE("fuzz corpus and regressions: OBJ", "[fuzz]") {
  CHECK(replay("obj", sm::fuzz::fuzz_obj) > 0);
}

TEST_CASE("fuzz corpus and regressions: OFF", "[fuzz]") {
  CHECK(replay("off", sm::fuzz::fuzz_off) > 0);
}

TEST_CASE("fuzz corpus and regressions: PLY", "[fuzz]") {
  CHECK(replay("ply", sm::fuzz::fuzz_ply) > 0);
}

TEST_CASE("fuzz corpus and regressions: config", "[fuzz]") {
  CHECK(replay("config", sm::fuzz::fuzz_config) > 0);
}

TEST_CASE("fuzz corpus and regressions: glTF", "[fuzz]") {
  CHECK(replay("gltf", sm::fuzz::fuzz_gltf) > 0);
}

TEST_CASE("fuzz corpus and regressions: point caches", "[fuzz]") {
  CHECK(replay("point_cache", sm::fuzz::fuzz_point_cache) > 0);
}
