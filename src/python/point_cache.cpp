/// seqmassage.read_point_cache() and write_point_cache(): PC2 and MDD point caches through the
/// library's reader and writer (io/point_cache.hpp), with their checks and messages.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include <pybind11/stl.h>  // PointCache.times

#include "io/point_cache.hpp"
#include "core/errors.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"

namespace sm::python {
namespace {

namespace fs = std::filesystem;

fs::path as_path(const py::handle& path) {
  return fs::path(py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>());
}

// The format: given ("pc2" or "mdd", any case), else the file's suffix.
PointCacheFormat format_of(const fs::path& path, const py::object& format) {
  std::string name;
  if (!format.is_none()) {
    name = py::str(format).cast<std::string>();
  } else {
    name = path.extension().string();
    if (!name.empty()) name.erase(0, 1);
  }
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (name == "pc2") return PointCacheFormat::Pc2;
  if (name == "mdd") return PointCacheFormat::Mdd;
  if (format.is_none())
    throw ConfigError(path.string() + ": a point cache's name ends in .pc2 or .mdd (or give "
                                      "format=\"pc2\" or \"mdd\")");
  throw ConfigError("format: expected \"pc2\" or \"mdd\", got \"" + name + "\"");
}

/// What read_point_cache returns.
struct PointCache {
  py::array_t<float> frames;  // F×n×3 float32, as stored
  std::string format;
  float start = 0.0f;
  float sample_rate = 1.0f;
  std::vector<float> times;
};

PointCache read_cache(const py::object& path_like, const py::object& format_name) {
  const fs::path path = as_path(path_like);
  const PointCacheFormat format = format_of(path, format_name);
  PointCacheHeader header;
  {
    py::gil_scoped_release unlocked;
    header = read_point_cache_header(path, format);
  }
  PointCache out;
  out.format = format == PointCacheFormat::Pc2 ? "pc2" : "mdd";
  out.start = header.start;
  out.sample_rate = header.sample_rate;
  out.times = header.times;
  // float32, the stored precision: the array is as large as the file's positions.
  out.frames = py::array_t<float>({static_cast<py::ssize_t>(header.frames),
                                   static_cast<py::ssize_t>(header.points), py::ssize_t{3}});
  float* data = out.frames.mutable_data();
  {
    py::gil_scoped_release unlocked;
    const std::string name = path.string();
    for (int f = 0; f < header.frames; ++f) {
      // The library's decoding, with its byte order and non-finite check naming the frame.
      const Positions V =
          decode_point_cache_frame(read_point_cache_frame_bytes(path, header, f), header, f, name);
      float* frame = data + static_cast<size_t>(f) * header.points * 3;
      for (Eigen::Index i = 0; i < V.rows(); ++i)
        for (int c = 0; c < 3; ++c) frame[i * 3 + c] = static_cast<float>(V(i, c));
    }
  }
  return out;
}

void write_cache(const py::object& path_like, const py::object& frames, const py::object& format_name,
                 float start, float sample_rate, const py::object& times) {
  const fs::path path = as_path(path_like);
  const PointCacheFormat format = format_of(path, format_name);
  const py::sequence seq = py::isinstance<py::sequence>(frames)
                               ? frames.cast<py::sequence>()
                               : py::list(frames).cast<py::sequence>();
  const int count = static_cast<int>(py::len(seq));
  if (count < 1) throw InputError("frames: a point cache needs at least one frame");
  const Positions first = to_positions(seq[0], "frames[0]");
  PointCacheTiming timing;
  timing.start = start;
  timing.sample_rate = sample_rate;
  if (format == PointCacheFormat::Mdd) {
    if (times.is_none()) {
      // Frame k at k / 24 s unless told: Blender's Mesh Cache default of 24 frames per second.
      for (int k = 0; k < count; ++k) timing.times.push_back(static_cast<float>(k) / 24.0f);
    } else {
      for (double t : to_numbers(times, "times")) timing.times.push_back(static_cast<float>(t));
      if (static_cast<int>(timing.times.size()) != count)
        throw ConfigError("times: expected " + std::to_string(count) + " frame times (one per "
                          "frame), got " + std::to_string(timing.times.size()));
    }
  }
  const int points = static_cast<int>(first.rows());
  write_point_cache(path, format, points, count, timing, [&](int k) {
    if (k == 0) return first;
    const std::string what = "frames[" + std::to_string(k) + "]";
    return to_positions(seq[k], what.c_str());
  });
}

}  // namespace

void bind_point_caches(py::module_& m) {
  py::class_<PointCache>(m, "PointCache", "What read_point_cache returns.")
      .def_readonly("frames", &PointCache::frames,
                    "every frame's positions, F×n×3 float32 (the stored precision)")
      .def_readonly("format", &PointCache::format, "\"pc2\" or \"mdd\"")
      .def_readonly("start", &PointCache::start, "PC2: the frame of the first sample")
      .def_readonly("sample_rate", &PointCache::sample_rate,
                    "PC2: frames from one sample to the next")
      .def_readonly("times", &PointCache::times, "MDD: each frame's time in seconds; PC2: []")
      .def("__len__", [](const PointCache& c) { return c.frames.shape(0); })
      .def("__repr__", [](const PointCache& c) {
        return "<seqmassage.PointCache " + c.format + " frames=" +
               std::to_string(c.frames.shape(0)) + " points=" +
               std::to_string(c.frames.shape(1)) + ">";
      });

  m.def("read_point_cache", &read_cache, py::arg("path"), py::arg("format") = py::none(),
        "read_point_cache(path, format=None) -> PointCache: a PC2 or MDD point cache (format "
        "\"pc2\" or \"mdd\"; None: from the file's suffix), read and checked as the sequence "
        "job reads one: the header against the file's size, every position finite. "
        "InputError names the file (and frame and vertex); IoError if it cannot be read.");
  m.def("write_point_cache", &write_cache, py::arg("path"), py::arg("frames"),
        py::arg("format") = py::none(), py::arg("start") = 0.0f, py::arg("sample_rate") = 1.0f,
        py::arg("times") = py::none(),
        "write_point_cache(path, frames, format=None, start=0.0, sample_rate=1.0, times=None): "
        "writes `frames` (an F×n×3 array or a sequence of n×3 arrays) as a PC2 or MDD cache "
        "(format from the suffix unless given), atomically (a temporary file renamed when "
        "complete), in float32 as the sequence job writes one. PC2: start and sample_rate in "
        "the header; MDD: times, one per frame in seconds (None: frame k at k/24 s). "
        "InputError for a frame of another size or a position not finite in float32.");
}

}  // namespace sm::python
