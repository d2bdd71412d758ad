// Mesh files by extension, and frame folders in natural order.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/frame_folder.hpp"
#include "io/mesh_file.hpp"
#include "core/errors.hpp"
#include "mesh/primitives.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using sm::test::error_of;

TEST_CASE("read_mesh and write_mesh choose the format by extension", "[mesh_file]") {
  const TriMesh m = make_torus(6, 4, 2.0, 0.5);
  sm::test::TempDir dir;
  for (const char* name : {"t.obj", "t.OFF", "t.Ply", "sub/t.OBJ"}) {
    INFO(name);
    write_mesh(dir / name, m);
    const TriMesh back = read_mesh(dir / name);
    CHECK(back.V == m.V);
    CHECK(back.F == m.F);
  }
  CHECK(read_file(dir / "t.obj").rfind("v ", 0) == 0);
  CHECK(read_file(dir / "t.OFF").rfind("OFF\n", 0) == 0);
  CHECK(read_file(dir / "t.Ply").rfind("ply\nformat binary_little_endian 1.0\n", 0) == 0);
  const auto stl = dir / "t.stl";
  CHECK(error_of<InputError>([&] { read_mesh(stl); }) ==
        "'" + stl.string() + "': unknown mesh file extension '.stl' (expected .obj, .off or .ply)");
  CHECK(error_of<InputError>([&] { write_mesh(dir / "noext", m); }) ==
        "'" + (dir / "noext").string() +
            "': unknown mesh file extension '' (expected .obj, .off or .ply)");
  CHECK(!std::filesystem::exists(stl));
}

TEST_CASE("natural order compares runs of digits by value", "[frames]") {
  CHECK(natural_less("frame_2", "frame_10"));
  CHECK(!natural_less("frame_10", "frame_2"));
  CHECK(natural_less("frame_0009.obj", "frame_0010.obj"));
  CHECK(natural_less("take2_frame10", "take10_frame2"));
  CHECK(natural_less("a2b9", "a2b10"));
  CHECK(natural_less("a2b10", "a3b1"));
  CHECK(natural_less("Frame_1", "frame_2"));  // case-insensitive
  CHECK(natural_less("frame", "frame_1"));
  CHECK(natural_less("x99999999999999999999998", "x99999999999999999999999"));  // no overflow
  // Equivalent names are ordered by their bytes, so the order is strict and total.
  CHECK(natural_less("frame_02", "frame_2"));
  CHECK(!natural_less("frame_2", "frame_02"));
  CHECK(natural_less("A", "a"));
  CHECK(!natural_less("a", "a"));

  std::vector<std::string> names = {"f10.obj", "f9.obj", "F1.obj",   "f1_2.obj", "f1_10.obj",
                                    "f01.obj", "f0.obj", "f100.obj", "f1.obj",   "f1_1.obj"};
  std::sort(names.begin(), names.end(),
            [](const std::string& a, const std::string& b) { return natural_less(a, b); });
  CHECK(names == std::vector<std::string>{"f0.obj", "F1.obj", "f01.obj", "f1.obj", "f1_1.obj",
                                          "f1_2.obj", "f1_10.obj", "f9.obj", "f10.obj",
                                          "f100.obj"});
}

TEST_CASE("list_frames returns the matching files in natural order", "[frames]") {
  sm::test::TempDir dir;
  for (const char* name : {"frame_10.obj", "frame_2.obj", "frame_1.OBJ", "notes.txt",
                           ".hidden_3.obj", "frame_3.obj.seqmassage-tmp", "frame_0.ply"}) {
    std::ofstream(dir / name) << "x";
  }
  const auto frames = list_frames(dir.path());
  REQUIRE(frames.size() == 3);
  CHECK(frames[0] == dir / "frame_1.OBJ");
  CHECK(frames[1] == dir / "frame_2.obj");
  CHECK(frames[2] == dir / "frame_10.obj");
  CHECK(list_frames(dir.path(), "PLY") == std::vector<std::filesystem::path>{dir / "frame_0.ply"});

  // A folder named like a frame is refused, not skipped (it would renumber the frames after it).
  std::filesystem::create_directories(dir / "frame_4.obj");
  CHECK_THROWS_WITH(list_frames(dir.path()), Catch::Contains("'frame_4.obj' is a folder"));
  std::filesystem::remove(dir / "frame_4.obj");

  const auto missing = dir / "missing";
  CHECK(error_of<IoError>([&] { list_frames(missing); }) ==
        "frame folder '" + missing.string() + "' does not exist");
  CHECK(error_of<InputError>([&] { list_frames(dir / "notes.txt"); }) ==
        "frame folder '" + (dir / "notes.txt").string() + "' is not a folder");
  CHECK(error_of<InputError>([&] { list_frames(dir.path(), ".off"); }) ==
        "frame folder '" + dir.path().string() + "' has no .off files");
}
