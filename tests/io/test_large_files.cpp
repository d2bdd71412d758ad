// Huge files: the readers and the OBJ writer do work linear in the size of the file. Not a timed
// test: the memory they allocate (counted by a replaced operator new) is compared between a file
// and one four times as large (linear: about 4x; quadratic: 16x), and the large files are big
// enough (tens of MB) that a reader quadratic in its lines would not finish within the ctest
// timeout. An error on the last line of a huge file is found and named like any other.
#include <unistd.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <string>

#include "io/atomic_file.hpp"
#include "io/gltf/gltf_load.hpp"
#include "io/obj.hpp"
#include "io/off.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"

namespace {

std::atomic<bool> g_counting{false};
std::atomic<size_t> g_bytes{0};
std::atomic<size_t> g_calls{0};

}  // namespace

// Every replaceable form but the aligned ones (left to the library, new and delete alike): a
// sanitizer's own operator new must never meet this operator delete.
namespace {
void* counted_malloc(std::size_t size) noexcept {
  if (g_counting.load(std::memory_order_relaxed)) {
    g_bytes += size;
    ++g_calls;
  }
  return std::malloc(size ? size : 1);
}
}  // namespace

void* operator new(std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = counted_malloc(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return counted_malloc(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}

using namespace sm;
namespace fs = std::filesystem;

namespace {

struct Work {
  size_t bytes = 0;  ///< allocated through operator new
  size_t calls = 0;
};

template <class F>
Work count(F&& f) {
  g_bytes = 0;
  g_calls = 0;
  g_counting = true;
  f();
  g_counting = false;
  return {g_bytes.load(), g_calls.load()};
}

// A textured grid of (k+1)² vertices and 2k² triangles as an OBJ with v, vt, vn and v/vt/vn
// corners: about 50k² bytes.
std::string grid_obj(int k) {
  const TriMesh g = make_grid(k, k, 1.0, 1.0);
  std::string text = "# generated\nmtllib grid.mtl\n";
  for (int i = 0; i < g.num_vertices(); ++i) {
    text += "v " + std::to_string(g.V(i, 0)) + " " + std::to_string(g.V(i, 1)) + " 0.25\n";
    text += "vt " + std::to_string(g.V(i, 0)) + " " + std::to_string(g.V(i, 1)) + "\n";
  }
  text += "vn 0 0 1\nusemtl grid\n";
  for (int t = 0; t < g.num_triangles(); ++t) {
    text += "f";
    for (int c = 0; c < 3; ++c) {
      const std::string v = std::to_string(g.F(t, c) + 1);
      text += " " + v + "/" + v + "/1";
    }
    text += "\n";
  }
  return text;
}

// Checks that `work(large)` is at most `factor` (4 for linear work) times 2 `work(small)`.
void check_linear(const Work& small, const Work& large, double factor, size_t small_size,
                  size_t large_size) {
  INFO("small: " << small.bytes << " bytes in " << small.calls << " allocations for a "
                 << small_size << "-byte file; large: " << large.bytes << " bytes in "
                 << large.calls << " allocations for " << large_size << " bytes");
  CHECK(double(large.bytes) <= 2.0 * factor * double(small.bytes));
  CHECK(double(large.calls) <= 2.0 * factor * double(small.calls) + 64);
  CHECK(large.bytes <= 24 * large_size);  // a few copies of the file, not a copy per line
}

}  // namespace

TEST_CASE("OBJ: reading and writing a huge file is linear", "[large]") {
  const std::string small = grid_obj(100), large = grid_obj(200);
  REQUIRE(large.size() > 3 * small.size());
  ObjFile f_small, f_large;
  const Work read_small = count([&] { f_small = parse_obj(small, "small.obj"); });
  const Work read_large = count([&] { f_large = parse_obj(large, "large.obj"); });
  check_linear(read_small, read_large, large.size() / double(small.size()), small.size(),
               large.size());
  CHECK(f_large.mesh.num_triangles() == 2 * 200 * 200);

  const Positions moved_small = f_small.mesh.V * 2.0, moved_large = f_large.mesh.V * 2.0;
  std::string out_small, out_large;
  const Work write_small = count([&] { out_small = format_obj(f_small, moved_small); });
  const Work write_large = count([&] { out_large = format_obj(f_large, moved_large); });
  check_linear(write_small, write_large, large.size() / double(small.size()), small.size(),
               large.size());

  // A huge file (tens of MB) parses, and an error on its last line is found and named.
  const std::string huge = grid_obj(500);
  REQUIRE(huge.size() > 30'000'000);
  const ObjFile f_huge = parse_obj(huge, "huge.obj");
  CHECK(f_huge.mesh.num_vertices() == 501 * 501);
  const int lines = 2 + 2 * 501 * 501 + 2 + 2 * 500 * 500;
  CHECK_THROWS_WITH(parse_obj(huge + "f 1 2 x\n", "huge.obj"),
                    "huge.obj:" + std::to_string(lines + 1) +
                        ": f: corner 3 'x': vertex index 'x' is not an integer");
}

TEST_CASE("OFF and PLY: reading a huge file is linear", "[large]") {
  const TriMesh small = make_grid(100, 100, 1.0, 1.0), large = make_grid(200, 200, 1.0, 1.0);
  const std::string off_small = format_off(small), off_large = format_off(large);
  const Work off_s = count([&] { parse_off(off_small, "small.off"); });
  const Work off_l = count([&] { parse_off(off_large, "large.off"); });
  check_linear(off_s, off_l, off_large.size() / double(off_small.size()), off_small.size(),
               off_large.size());
  for (const bool binary : {false, true}) {
    INFO((binary ? "binary" : "ASCII") << " PLY");
    const std::string ply_small = format_ply(small, nullptr, binary);
    const std::string ply_large = format_ply(large, nullptr, binary);
    const Work s = count([&] { parse_ply(ply_small, "small.ply"); });
    const Work l = count([&] { parse_ply(ply_large, "large.ply"); });
    check_linear(s, l, ply_large.size() / double(ply_small.size()), ply_small.size(),
                 ply_large.size());
  }
  const TriMesh huge = make_grid(800, 800, 1.0, 1.0);
  const std::string off_huge = format_off(huge);
  REQUIRE(off_huge.size() > 20'000'000);
  CHECK(parse_off(off_huge, "huge.off").num_triangles() == 2 * 800 * 800);
  CHECK(parse_ply(format_ply(huge, nullptr, true), "huge.ply").num_vertices() == 801 * 801);
}

TEST_CASE("OBJ: the memory bound holds for the densest file (bare vertex lines)", "[large]") {
  // "v 0 0 0\n" is 8 bytes for 24 bytes of doubles: the worst ratio of the format. Everything
  // allocated while reading (the text, the growing arrays and the mesh) stays within 24x the file.
  std::string text;
  for (int i = 0; i < 300000; ++i) text += "v 0 0 0\n";
  text += "f 1 2 3\n";
  ObjFile f;
  const Work w = count([&] { f = parse_obj(text, "dense.obj"); });
  INFO(w.bytes << " bytes allocated for a " << text.size() << "-byte file");
  CHECK(w.bytes <= 24 * text.size());
  CHECK(f.mesh.num_vertices() == 300000);
}

TEST_CASE("glTF: a 1.6 KB file claiming 4e8 or 2^31-1 elements is refused cheaply", "[large]") {
  // One triangle (36 bytes of positions, in a data: URI) under a node translated from t = 0 to 1,
  // whose POSITION count claims far more.
  const std::string data =
      "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAA=";
  const fs::path dir =
      fs::temp_directory_path() / ("seqmassage-count-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* claimed : {"400000000", "2147483647"}) {
    std::string doc = R"({"asset": {"version": "2.0"},
      "buffers": [{"byteLength": 68, "uri": "data:application/octet-stream;base64,)" + data +
                      R"("}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36,
                       "byteLength": 8}, {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": )" +
                      std::string(claimed) + R"(},
        {"bufferView": 1, "componentType": 5126, "type": "SCALAR", "count": 2,
         "min": [0], "max": [1]},
        {"bufferView": 2, "componentType": 5126, "type": "VEC3", "count": 2}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}],
      "animations": [{"samplers": [{"input": 1, "output": 2}],
                      "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]})";
    doc += std::string(1600 - std::min<size_t>(doc.size(), 1600), ' ');
    const fs::path file = dir / "count.gltf";
    write_file_atomic(file, doc);
    std::string message;
    const Work w = count([&] {
      try {
        load_gltf_sequence({file, "", "", std::nullopt});
      } catch (const InputError& e) {
        message = e.what();
      }
    });
    INFO(claimed << ": " << w.bytes << " bytes allocated");
    CHECK_THAT(message, Catch::Contains("accessors[0]: data needs bytes 0.."));
    CHECK(w.bytes < 1'000'000);
  }
  fs::remove_all(dir);
}
