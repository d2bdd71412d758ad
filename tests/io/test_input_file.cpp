// Only regular files are read, without blocking (io/input_file.hpp): a FIFO, a device or a folder
// named as an input mesh is an error naming it; binary and UTF-16 files named .obj say so; finite
// coordinates too large for the geometry name the file, line and value.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>

#include "io/atomic_file.hpp"
#include "io/input_file.hpp"
#include "io/mesh_file.hpp"
#include "io/obj.hpp"
#include "io/off.hpp"
#include "io/ply.hpp"
#include "io/sha256.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

namespace sm {
namespace {

namespace fs = std::filesystem;
using Catch::Contains;
using test::error_of;

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

TEST_CASE("a FIFO, a device or a folder given as an input file is refused without blocking") {
  const test::TempDir dir("input_kinds");
  const fs::path fifo = dir / "frame.obj";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // no writer: a blocking open would hang
  const std::string fifo_error =
      "'" + fifo.string() + "': not a regular file (a FIFO); only regular files are read";
  CHECK(error_of<InputError>([&] { read_obj(fifo); }) == fifo_error);
  CHECK(error_of<InputError>([&] { read_mesh(fifo); }) == fifo_error);
  CHECK(error_of<InputError>([&] { sha256_file(fifo); }) == fifo_error);
  const fs::path zero = dir / "zero.ply";
  fs::create_symlink("/dev/zero", zero);  // would be read without end
  CHECK(error_of<InputError>([&] { read_mesh(zero); }) ==
        "'" + zero.string() +
            "': not a regular file (a character device); only regular files are read");
  CHECK_THROWS_AS(check_input_file(zero), InputError);
  fs::create_directories(dir / "folder.off");
  CHECK(error_of<IoError>([&] { read_mesh(dir / "folder.off"); }) ==
        "cannot read '" + (dir / "folder.off").string() + "': Is a directory");
  CHECK(error_of<IoError>([&] { read_mesh(dir / "missing.obj"); }) ==
        "cannot open '" + (dir / "missing.obj").string() + "': No such file or directory");
  // A regular file through a symlink is read, and its size is known before reading.
  write_file_atomic(dir / "t.obj", kTriangle);
  fs::create_symlink("t.obj", dir / "link.obj");
  CHECK(read_mesh(dir / "link.obj").num_triangles() == 1);
  CHECK(InputFile(dir / "link.obj").size() == std::string(kTriangle).size());
  CHECK(read_input_file(dir / "link.obj") == kTriangle);
  CHECK(fs::is_fifo(fifo));  // inputs untouched
}

std::string utf16(const std::string& ascii, bool little, bool bom) {
  std::string out;
  if (bom) out = little ? "\xFF\xFE" : "\xFE\xFF";
  for (char c : ascii) out += little ? std::string{c, '\0'} : std::string{'\0', c};
  return out;
}

TEST_CASE("a binary or UTF-16 file named .obj says it is not a text OBJ and which encoding") {
  const std::string start = "x.obj: not a text OBJ file: ";
  CHECK(error_of<InputError>([] { parse_obj(utf16(kTriangle, true, true), "x.obj"); }) ==
        start + "it is UTF-16 (little-endian, byte order mark FF FE); OBJ is ASCII or UTF-8 text");
  CHECK(error_of<InputError>([] { parse_obj(utf16(kTriangle, false, true), "x.obj"); }) ==
        start + "it is UTF-16 (big-endian, byte order mark FE FF); OBJ is ASCII or UTF-8 text");
  CHECK(error_of<InputError>([] { parse_obj(utf16(kTriangle, true, false), "x.obj"); }) ==
        start +
            "it looks like UTF-16 little-endian (every other byte is NUL); OBJ is ASCII or UTF-8 "
            "text");
  CHECK(error_of<InputError>([] { parse_obj(utf16(kTriangle, false, false), "x.obj"); }) ==
        start +
            "it looks like UTF-16 big-endian (every other byte is NUL); OBJ is ASCII or UTF-8 text");
  std::string binary = "\x7F" "ELF\x02\x01\x01";
  binary += std::string(64, '\0') + "\x01\x02\x03";
  CHECK(error_of<InputError>([&] { parse_obj(binary, "x.obj"); }) ==
        start + "it holds NUL bytes (binary data); OBJ is ASCII or UTF-8 text");
  // UTF-8 (with or without byte order mark) and Latin-1 comments are text.
  CHECK(parse_obj(std::string("\xEF\xBB\xBF# caf\xC3\xA9 \xE9\n") + kTriangle, "x.obj")
            .mesh.num_triangles() == 1);
}

TEST_CASE("finite coordinates too large for the geometry name file, line and value") {
  const std::string too_large =
      "' is too large (more than 1e18 in magnitude: the geometry would overflow)";
  CHECK(error_of<InputError>([] {
          parse_obj("v 0 0 0\nv 1 1e308 0\nv 0 1 0\nf 1 2 3\n", "x.obj");
        }) == "x.obj:2: v: coordinate y '1e308" + too_large);
  CHECK(error_of<InputError>([] {
          parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 -2e18\nf 1 2 3\n", "x.obj");
        }) == "x.obj:3: v: coordinate z '-2e18" + too_large);
  CHECK(parse_obj("v 0 0 0\nv 1e18 0 0\nv 0 1e18 0\nf 1 2 3\n", "x.obj").mesh.num_vertices() == 3);
  CHECK_THAT(error_of<InputError>([] {
               parse_off("OFF\n3 1 0\n0 0 0\n1e300 0 0\n0 1 0\n3 0 1 2\n", "x.off");
             }),
             Contains("vertex 1: coordinate x '1e300" + too_large));
  CHECK_THAT(error_of<InputError>([] {
               parse_ply("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nelement face 1\n"
                         "property list uchar int vertex_indices\nend_header\n"
                         "0 0 0\n1 0 0\n0 3e38 0\n3 0 1 2\n",
                         "x.ply");
             }),
             Contains("y 3e+38 is too large (more than 1e18 in magnitude"));
}

}  // namespace
}  // namespace sm
