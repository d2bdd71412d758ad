// The bad-input catalogue for mesh files and output files: truncated files,
// non-finite values in every format, and writes that fail (a folder that cannot be created, a
// full disk) leave neither a partial file nor a temporary one.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/mesh_file.hpp"
#include "io/obj.hpp"
#include "io/off.hpp"
#include "io/ply.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using sm::test::error_of;
namespace fs = std::filesystem;

namespace {

const std::string kTri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

std::string obj_error(const std::string& text) {
  return error_of<InputError>([&] { parse_obj(text, "bad.obj"); });
}

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little-endian machine, like the format
  out.append(bytes, sizeof(T));
}

// A binary PLY triangle whose vertex 1 has coordinate y = `y`.
std::string binary_ply(float y) {
  std::string data =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  for (float v : {0.f, 0.f, 0.f, 1.f, y, 0.f, 0.f, 1.f, 0.f}) put(data, v);
  put(data, uint8_t{3});
  for (int32_t i : {0, 1, 2}) put(data, i);
  return data;
}

// Files in `dir` (recursively) whose names carry the temporary suffix.
int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find(kTempSuffix) != std::string::npos) ++n;
  }
  return n;
}

}  // namespace

TEST_CASE("truncated mesh files name the line and what is missing", "[errors]") {
  // An OBJ cut inside a statement: the last statement is incomplete.
  CHECK(obj_error(kTri + "f 1 2 3\nv 0 0") ==
        "bad.obj:5: v: expected 3 coordinates (x y z), found 2");
  CHECK(obj_error(kTri + "f 1 2") == "bad.obj:4: f: a face needs at least 3 corners, found 2");
  CHECK(obj_error(kTri + "f 1 2 3/") ==
        "bad.obj:4: f: corner 3 '3/': expected v, v/vt, v//vn or v/vt/vn");
  // An OBJ cut before its faces.
  CHECK(obj_error(kTri) == "bad.obj: no faces (no 'f' statement)");
  // OFF and PLY cut in their data.
  CHECK(error_of<InputError>([] { parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1", "cut.off"); }) ==
        "cut.off:5: vertex 2: coordinate z is missing");
  const std::string ply = binary_ply(0.f);
  CHECK(error_of<InputError>([&] { parse_ply(ply.substr(0, ply.size() - 3), "cut.ply"); }) ==
        "cut.ply: face 0: vertex_indices: the data ends early (binary, byte " +
            std::to_string(ply.size() - 4) + ")");
  CHECK(error_of<InputError>([&] { parse_ply(ply.substr(0, 60), "cut.ply"); }) ==
        "cut.ply:4: unknown header keyword 'propert'");
  CHECK(error_of<InputError>([&] {
          parse_ply(ply.substr(0, ply.find("end_header")), "cut.ply");
        }) == "cut.ply: the PLY header has no end_header line");
}

TEST_CASE("non-finite values are refused in every format and every field", "[errors]") {
  CHECK(obj_error(kTri + "vt nan 0\nf 1 2 3\n") ==
        "bad.obj:4: vt: coordinate u 'nan' is not finite");
  CHECK(obj_error("v 0 0 0 1 inf\n") ==
        "bad.obj:1: v: extra value 2 (w or colour) 'inf' is not finite");
  CHECK(obj_error("v 0 0 -1e400\n") == "bad.obj:1: v: coordinate z '-1e400' is not finite");
  CHECK(error_of<InputError>([] {
          parse_off("OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", "bad.off");
        }) == "bad.off:5: vertex 2: coordinate y 'inf' is not finite");
  CHECK(error_of<InputError>([] { parse_ply(binary_ply(std::nanf("")), "bad.ply"); }) ==
        "bad.ply: vertex 1: y is not finite");
  CHECK(error_of<InputError>([] { parse_ply(binary_ply(-HUGE_VALF), "bad.ply"); }) ==
        "bad.ply: vertex 1: y is not finite");
}

TEST_CASE("an OBJ face may not refer to a vt or vn that is missing", "[errors]") {
  CHECK(obj_error(kTri + "vt 0 0\nvt 1 0\nf 1/1 2/2 3/3\n") ==
        "bad.obj:6: f: corner 3 '3/3': texture coordinate index 3 is out of range (the file has 2 "
        "texture coordinates)");
  CHECK(obj_error(kTri + "vn 0 0 1\nf 1//1 2//1 3//-2\n") ==
        "bad.obj:5: f: corner 3 '3//-2': relative normal index -2 is out of range (1 normals "
        "defined before this line)");
  CHECK(obj_error(kTri + "f 1/1/1 2/1/1 3/1/1\n") ==
        "bad.obj:4: f: corner 1 '1/1/1': texture coordinate index 1 is out of range (the file has "
        "0 texture coordinates)");
}

TEST_CASE("an output folder that cannot be created names the folder and nothing is written",
          "[errors]") {
  // A regular file where a folder is needed: refused even for root, unlike a read-only folder.
  sm::test::TempDir dir;
  std::ofstream(dir / "file") << "x";
  const fs::path out = dir / "file" / "out" / "frame.obj";
  const std::string message = error_of<IoError>([&] { write_file_atomic(out, "v 0 0 0\n"); });
  CHECK_THAT(message,
             Catch::StartsWith("cannot create folder '" + (dir / "file" / "out").string() + "': "));
  CHECK(temporaries_in(dir.path()) == 0);
}

TEST_CASE("a full disk fails the write with the file's name and leaves no partial file",
          "[errors]") {
  // RLIMIT_FSIZE makes write() fail with EFBIG beyond the limit, as a full disk fails with ENOSPC;
  // it is set in a child process (SIGXFSZ ignored), which reports the message through a pipe.
  sm::test::TempDir dir;
  const fs::path target = dir / "frames" / "frame_0001.obj";
  write_file_atomic(target, "the previous complete version\n");
  const std::string big(1 << 20, 'v');
  int fds[2];
  REQUIRE(::pipe(fds) == 0);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    ::close(fds[0]);
    ::signal(SIGXFSZ, SIG_IGN);
    const struct rlimit limit = {4096, 4096};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(2);
    std::string message = "no error";
    try {
      write_file_atomic(target, big);
    } catch (const IoError& e) {
      message = e.what();
    }
    const ssize_t written = ::write(fds[1], message.data(), message.size());
    ::_exit(written == static_cast<ssize_t>(message.size()) ? 0 : 3);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[512];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) message.append(buffer, n);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  CHECK(message == "cannot write '" + target.string() + "': " + std::strerror(EFBIG));
  // The destination keeps its previous complete content; no temporary file is left.
  CHECK(read_file(target) == "the previous complete version\n");
  CHECK(temporaries_in(dir.path()) == 0);
}

TEST_CASE("an unknown mesh file extension is named", "[errors]") {
  sm::test::TempDir dir;
  std::ofstream(dir / "mesh.stl") << "solid x\n";
  const std::string message = error_of<InputError>([&] { read_mesh(dir / "mesh.stl"); });
  CHECK_THAT(message, Catch::Contains("mesh.stl"));
  CHECK_THAT(message, Catch::Contains(".stl"));
}

TEST_CASE("normals of huge triangles are recomputed or kept, never written as NaN", "[errors]") {
  // Found by fuzzing: coordinates near 1e308 overflowed the normals' sum and wrote "vn -nan".
  // Readers now refuse coordinates beyond 1e18; the writer must still never write a NaN normal.
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 1 0 # kept\nf 1//1 2//1 3//1\nf 1//2 2//2 3//2\n";
  const ObjFile f = parse_obj(text, "huge.obj");
  for (const double big : {1e18, 1e150, 1e200, 1e307}) {
    INFO("coordinates of " << big);
    Positions V = f.mesh.V * big;
    V(0, 2) = big / 4;  // tilt the triangle
    const std::string written = format_obj(f, V);
    CHECK(written.find("nan") == std::string::npos);
    CHECK(written.find("\nvn ") != std::string::npos);
  }
  CHECK_THROWS_WITH(parse_obj("v 0 0 0\nv 1e150 0 0\nv 0 1 0\nf 1 2 3\n", "huge.obj"),
                    Catch::Contains("huge.obj:2: v: coordinate x '1e150' is too large"));
}
