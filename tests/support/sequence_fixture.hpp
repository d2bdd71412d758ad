#pragma once
/// Small generated sequences for the sequence job's robustness tests (numerical failures, resume,
// shards): a folder of drifted tube frames and a config reading it, and helpers to compare
// output folders byte for byte.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "pipeline/sequence/sequence_options.hpp"
#include "pipeline/sequence/synthetic.hpp"

namespace sm::test {

// A drifting tube of `frames` frames, `segments` × 10 vertices.
inline SyntheticOptions small_tube(int frames = 6, int segments = 12) {
  SyntheticOptions c;
  c.frames = frames;
  c.segments = segments;
  c.rings = 10;
  return c;
}

// Frames of `tube` in dir/in, and a config reading them into dir/out (8 iterations, per-triangle
// tables, no timings: every output byte is reproducible).
inline SequenceJobOptions tube_job(const std::filesystem::path& dir, const SyntheticOptions& tube) {
  write_synthetic_sequence(make_synthetic_sequence(tube), dir / "in", dir / "gt");
  SequenceJobOptions c;
  c.input.frames = dir / "in";
  c.output.dir = dir / "out";
  c.output.per_triangle_csv = true;
  c.output.timings = false;
  c.output.html = false;  // report.html: test_html_report.cpp and the merge test turn it on
  c.massage.iterations = 8;
  c.threads = 2;
  return c;
}

// Every regular file under `dir` with its bytes, by path relative to `dir`; files whose name
// matches `skip` (a substring) are left out.
inline std::map<std::string, std::string> folder_bytes(const std::filesystem::path& dir,
                                                       const std::string& skip = "") {
  std::map<std::string, std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string rel = std::filesystem::relative(entry.path(), dir).generic_string();
    if (!skip.empty() && rel.find(skip) != std::string::npos) continue;
    files[rel] = read_file(entry.path());
  }
  return files;
}

// The file names of folder_bytes.
inline std::vector<std::string> names_of(const std::map<std::string, std::string>& files) {
  std::vector<std::string> names;
  for (const auto& [name, bytes] : files) names.push_back(name);
  return names;
}

// Checks that the folders `a` and `b` hold the same files with the same bytes (leaving out those
// whose name matches `skip`); returns folder_bytes(a, skip).
inline std::map<std::string, std::string> compare_folders(const std::filesystem::path& a,
                                                          const std::filesystem::path& b,
                                                          const std::string& skip = "") {
  const auto left = folder_bytes(a, skip), right = folder_bytes(b, skip);
  CHECK(names_of(left) == names_of(right));
  for (const auto& [name, bytes] : left) {
    INFO(name);
    REQUIRE(right.count(name));
    CHECK(right.at(name) == bytes);
  }
  return left;
}

// Rewrites the `v` lines of an OBJ file through `f(vertex index, x, y, z)`.
template <class F>
void edit_obj_vertices(const std::filesystem::path& file, F&& f) {
  const std::string text = read_file(file);
  std::string out;
  int v = 0;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    if (line.rfind("v ", 0) == 0) {
      double x = 0, y = 0, z = 0;
      std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z);
      f(v++, x, y, z);
      char buffer[128];
      std::snprintf(buffer, sizeof buffer, "v %.17g %.17g %.17g", x, y, z);
      line = buffer;
    }
    out += line + "\n";
    at = end + 1;
  }
  write_file_atomic(file, out);
}

}  // namespace sm::test
