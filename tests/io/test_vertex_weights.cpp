// Per-vertex weight files (massage.vertex_weights): text and a PLY vertex property, and the
// messages for a bad token, a value outside [0, 1] and a count that is not the template's.
#include <catch2/catch.hpp>

#include "io/atomic_file.hpp"
#include "io/vertex_weights.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;

TEST_CASE("text vertex weights: any blanks and line breaks, messages name the line",
          "[io][weights]") {
  CHECK(parse_vertex_weights("1 0.5\n\n  0\t0.25\r\n1e-1", "w.txt") ==
        std::vector<double>{1.0, 0.5, 0.0, 0.25, 0.1});
  CHECK(parse_vertex_weights("", "w.txt").empty());
  CHECK(test::error_of<InputError>([] { parse_vertex_weights("1\n0.5 abc\n", "w.txt"); }) ==
        "w.txt:2: 'abc' is not a number");
  CHECK(test::error_of<InputError>([] { parse_vertex_weights("1\n1\n1.5\n", "w.txt"); }) ==
        "w.txt:3: weight 1.5 is not a number in [0, 1] (vertex 2, 0-based)");
  CHECK(test::error_of<InputError>([] { parse_vertex_weights("nan", "w.txt"); }) ==
        "w.txt:1: weight nan is not a number in [0, 1] (vertex 0, 0-based)");
}

TEST_CASE("vertex weights from a file: count against the template, PLY property",
          "[io][weights]") {
  test::TempDir dir("vertex_weights");
  write_file_atomic(dir / "w.txt", "1 0.5 0\n");
  CHECK(read_vertex_weights(dir / "w.txt", 3, "t.obj") == std::vector<double>{1.0, 0.5, 0.0});
  CHECK(test::error_of<InputError>([&] { read_vertex_weights(dir / "w.txt", 4, "t.obj"); }) ==
        "massage.vertex_weights: " + (dir / "w.txt").string() +
            " has 3 weights, but the template, t.obj, has 4 vertices");
  CHECK_THROWS_AS(read_vertex_weights(dir / "missing.txt", 3, "t.obj"), IoError);

  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float quality\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0 1\n1 0 0 0.25\n0 1 0 0\n3 0 1 2\n";
  write_file_atomic(dir / "w.ply", ply);
  CHECK(read_vertex_weights(dir / "w.ply#quality", 3, "t.obj") ==
        std::vector<double>{1.0, 0.25, 0.0});
  CHECK(test::error_of<InputError>([&] { read_vertex_weights(dir / "w.ply#mask", 3, "t.obj"); }) ==
        (dir / "w.ply").string() + ": the vertex element has no scalar property 'mask'");
  write_file_atomic(dir / "bad.ply", ply.substr(0, ply.find("1 0 0 0.25")) + "1 0 0 2\n0 1 0 0\n3 0 1 2\n");
  CHECK(test::error_of<InputError>([&] { read_vertex_weights(dir / "bad.ply#quality", 3, "t"); }) ==
        (dir / "bad.ply").string() + ": vertex 1: quality = 2 is not a weight in [0, 1]");
}

TEST_CASE("a weights file stops at the first number past the template's vertex count",
          "[io][weights]") {
  // Everything after the count's first extra number is not parsed: a bad token, or a value
  // outside [0, 1], past it is never seen.
  CHECK(parse_vertex_weights("1 0.5 0 0.25 abc 7", "w.txt", 4) ==
        std::vector<double>{1.0, 0.5, 0.0, 0.25});
  CHECK(parse_vertex_weights("1\n0.5\n0\nnot numbers at all", "w.txt", 3) ==
        std::vector<double>{1.0, 0.5, 0.0});
  test::TempDir dir("vertex_weights_long");
  // 64 vertices and 100000 more numbers, then text that is no number: refused for the count.
  std::string text;
  for (int i = 0; i < 100064; ++i) text += "0.5\n";
  text += "garbage\n";
  write_file_atomic(dir / "w.txt", text);
  CHECK(test::error_of<InputError>([&] { read_vertex_weights(dir / "w.txt", 64, "t.obj"); }) ==
        "massage.vertex_weights: " + (dir / "w.txt").string() +
            " has more than 64 weights, but the template, t.obj, has 64 vertices");
  // Exactly the count is accepted, and fewer keep their message.
  std::string exact;
  for (int i = 0; i < 64; ++i) exact += "1 ";
  write_file_atomic(dir / "exact.txt", exact);
  CHECK(read_vertex_weights(dir / "exact.txt", 64, "t.obj").size() == 64);
  CHECK(test::error_of<InputError>([&] { read_vertex_weights(dir / "exact.txt", 65, "t.obj"); }) ==
        "massage.vertex_weights: " + (dir / "exact.txt").string() +
            " has 64 weights, but the template, t.obj, has 65 vertices");
}
