// Fuzz target: the glTF loading path (io/gltf/gltf_load.hpp), from the file's bytes to evaluated frames.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz_targets.hpp"
#include "io/gltf/gltf_load.hpp"
#include "core/errors.hpp"

namespace sm::fuzz {
namespace {

namespace fs = std::filesystem;

// The loader takes a file (buffers and images may be other files beside it), so every input is
// written to the same file in a folder of this process, removed at exit: in /dev/shm where there
// is one (ten times as many runs per second as a disk-backed /tmp).
class ScratchFile {
 public:
  ScratchFile() : dir_(base() / ("seqmassage-fuzz-gltf-" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
  }
  ~ScratchFile() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const uint8_t* data, size_t size) const {
    const fs::path file = dir_ / "input.glb";
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) throw FuzzFinding("cannot write the scratch file " + file.string());
    return file;
  }

 private:
  static fs::path base() {
    std::error_code ec;
    if (fs::is_directory("/dev/shm", ec) && ::access("/dev/shm", W_OK) == 0) return "/dev/shm";
    return fs::temp_directory_path();
  }
  fs::path dir_;
};

void check_sequence(const GltfSequence& s) {
  const int n = s.rest.num_vertices();
  try {
    validate_mesh(s.rest, "rest mesh");
  } catch (const InputError& e) {
    throw FuzzFinding(std::string("accepted an invalid rest mesh: ") + e.what());
  }
  expect(n > 0 && s.rest.num_triangles() > 0, "accepted a mesh without triangles");
  expect(s.weld_map.size() == size_t(s.gltf_vertices), "weld_map has the wrong size");
  for (int w : s.weld_map) expect(w >= -1 && w < n, "weld_map entry out of range");
  expect(!s.times.empty(), "a sequence without frames");
  for (size_t k = 0; k < s.times.size(); ++k) {
    expect(std::isfinite(s.times[k]), "a frame time is not finite");
    expect(k == 0 || s.times[k] > s.times[k - 1], "frame times do not increase");
  }
  for (const int frame : {0, s.num_frames() / 2, s.num_frames() - 1}) {
    const WeldedFrame f = evaluate_gltf_frame(s, frame);
    expect(f.V.rows() == n, "an evaluated frame has the wrong number of vertices");
  }
}

}  // namespace

void fuzz_gltf(const uint8_t* data, size_t size) {
  static const ScratchFile scratch;
  GltfInputOptions options;
  options.file = scratch.write(data, size);
  GltfSequence sequence;
  try {
    sequence = load_gltf_sequence(options);
  } catch (const InputError&) {
    return;
  }
  check_sequence(sequence);
}

}  // namespace sm::fuzz
