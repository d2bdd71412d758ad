#include "io/point_cache.hpp"
#include "io/point_cache_timing.hpp"

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "io/atomic_file.hpp"
#include "core/coordinate_limit.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

constexpr char kPc2Magic[12] = {'P', 'O', 'I', 'N', 'T', 'C', 'A', 'C', 'H', 'E', '2', '\0'};
constexpr uint64_t kPc2HeaderBytes = 32;  // magic, version, points, start, rate, samples
constexpr uint64_t kMddHeaderBytes = 8;   // frames, points (then the frame times)
// A PC2's frame numbers start + k × rate (k below the sample count) lie within 1e18 in
// magnitude, the coordinate limit: a cache written from a selection of them (start = a selected
// frame's number, rate = the step between two) then keeps them finite in float32, and reads back.
constexpr double kMaxFrameNumber = 1e18;

bool big_endian(PointCacheFormat format) {
  return format == PointCacheFormat::Mdd;
}

uint32_t load_u32(const char* p, bool big) {
  const auto b = [&](int i) { return uint32_t(static_cast<unsigned char>(p[i])); };
  return big ? b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3) : b(3) << 24 | b(2) << 16 | b(1) << 8 | b(0);
}

int32_t load_i32(const char* p, bool big) {
  const uint32_t u = load_u32(p, big);
  int32_t i;
  std::memcpy(&i, &u, 4);
  return i;
}

float load_f32(const char* p, bool big) {
  const uint32_t u = load_u32(p, big);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

void store_u32(std::string& out, uint32_t u, bool big) {
  for (int i = 0; i < 4; ++i) out += char((u >> (big ? 24 - 8 * i : 8 * i)) & 0xff);
}

void store_i32(std::string& out, int32_t i, bool big) {
  uint32_t u;
  std::memcpy(&u, &i, 4);
  store_u32(out, u, big);
}

void store_f32(std::string& out, float f, bool big) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  store_u32(out, u, big);
}

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.9g", x);
  return buffer;
}

// "frame F of P points": checks a count read from the header.
int count(int32_t value, const char* what, const std::string& name) {
  if (value < 1)
    throw InputError(name + ": the header's " + what + " is " + std::to_string(value) +
                     " (expected at least 1)");
  return value;
}

// The bytes the counts need, in decimal: exact even when they overflow 64 bits.
__extension__ typedef unsigned __int128 Uint128;  // GCC and Clang

std::string needed_bytes(const PointCacheHeader& h) {
  Uint128 n = Uint128(h.frames) * h.frame_bytes() + h.data_offset;
  std::string digits;
  do {
    digits.insert(digits.begin(), char('0' + int(n % 10)));
    n /= 10;
  } while (n > 0);
  return digits;
}

// Throws unless the counts give exactly `file_size` bytes (computed without overflow: the
// frame count is compared with what the bytes after the header can hold).
void check_size(const PointCacheHeader& h, uint64_t file_size, const std::string& name) {
  const std::string counts = std::to_string(h.frames) + " frames of " +
                             std::to_string(h.points) + " points";
  if (file_size < h.data_offset)
    throw InputError(name + ": " + std::to_string(file_size) + " bytes, too short for the header (" +
                     std::to_string(h.data_offset) + " bytes for " + counts + ")");
  const uint64_t data = file_size - h.data_offset;
  if (data / h.frame_bytes() < uint64_t(h.frames))
    throw InputError(name + ": truncated: " + std::to_string(file_size) + " bytes, but the header's " +
                     counts + " need " + needed_bytes(h));
  if (data != uint64_t(h.frames) * h.frame_bytes())
    throw InputError(name + ": " + std::to_string(file_size) + " bytes, but the header's " + counts +
                     " need " + needed_bytes(h) + " (trailing bytes, or wrong counts)");
}

}  // namespace

std::string pc2_timing_problem(float start, float sample_rate, int samples) {
  if (!std::isfinite(start) || !std::isfinite(sample_rate))
    return "start frame (" + number(start) + ") or sample rate (" + number(sample_rate) +
           ") is not finite";
  if (!(sample_rate > 0.0f))
    return "sample rate " + number(sample_rate) +
           " is not positive (it is the number of frames from one sample to the next)";
  const double last = double(start) + double(std::max(samples, 1) - 1) * double(sample_rate);
  if (std::fabs(double(start)) > kMaxFrameNumber || std::fabs(last) > kMaxFrameNumber)
    return "frames run from " + number(start) + " to " + number(last) +
           " (start frame + (samples - 1) x sample rate), beyond 1e18 in magnitude";
  return "";
}

const char* point_cache_format_label(PointCacheFormat format) {
  return format == PointCacheFormat::Pc2 ? "PC2" : "MDD";
}

PointCacheHeader parse_point_cache_header(std::string_view data, uint64_t file_size,
                                          PointCacheFormat format, const std::string& name) {
  const bool big = big_endian(format);
  PointCacheHeader h;
  h.format = format;
  const uint64_t fixed = format == PointCacheFormat::Pc2 ? kPc2HeaderBytes : kMddHeaderBytes;
  if (file_size < fixed || data.size() < fixed)
    throw InputError(name + ": " + std::to_string(file_size) + " bytes, too short for a " +
                     point_cache_format_label(format) + " header (" + std::to_string(fixed) +
                     " bytes)");
  const char* p = data.data();
  if (format == PointCacheFormat::Pc2) {
    if (std::memcmp(p, kPc2Magic, sizeof kPc2Magic) != 0)
      throw InputError(name + ": not a PC2 file (it does not start with \"POINTCACHE2\\0\")");
    const int32_t version = load_i32(p + 12, big);
    if (version != 1)
      throw InputError(name + ": PC2 version " + std::to_string(version) + " (only 1 is known)");
    h.points = count(load_i32(p + 16, big), "point count", name);
    h.start = load_f32(p + 20, big);
    h.sample_rate = load_f32(p + 24, big);
    h.frames = count(load_i32(p + 28, big), "sample count", name);
    if (const std::string problem = pc2_timing_problem(h.start, h.sample_rate, h.frames);
        !problem.empty())
      throw InputError(name + ": the header's " + problem);
    h.data_offset = kPc2HeaderBytes;
    check_size(h, file_size, name);
    return h;
  }
  h.frames = count(load_i32(p, big), "frame count", name);
  h.points = count(load_i32(p + 4, big), "point count", name);
  h.data_offset = kMddHeaderBytes + 4 * uint64_t(h.frames);
  check_size(h, file_size, name);  // before the times are allocated
  if (data.size() < h.data_offset)
    throw std::logic_error("parse_point_cache_header: the MDD frame times were not given");
  h.times.resize(size_t(h.frames));
  for (int f = 0; f < h.frames; ++f) {
    h.times[size_t(f)] = load_f32(p + kMddHeaderBytes + 4 * uint64_t(f), big);
    if (!std::isfinite(h.times[size_t(f)]))
      throw InputError(name + ": frame " + std::to_string(f) + ": non-finite frame time " +
                       number(h.times[size_t(f)]));
  }
  return h;
}

PointCacheHeader read_point_cache_header(const fs::path& file, PointCacheFormat format) {
  const std::string name = "'" + file.string() + "'";
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status))
    throw IoError("cannot open " + name + ": " + (ec ? ec.message() : "no such file"));
  if (!fs::is_regular_file(status))
    throw InputError(name + ": not a regular file (a " + point_cache_format_label(format) +
                     " point cache is a file)");
  const uint64_t size = fs::file_size(file, ec);
  if (ec) throw IoError("cannot read " + name + ": " + ec.message());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw IoError("cannot open " + name + ": " + std::strerror(errno ? errno : ENOENT));
  const auto read = [&](std::string& into, uint64_t bytes) {
    into.resize(size_t(std::min(bytes, size)));
    in.read(into.data(), std::streamsize(into.size()));
    if (uint64_t(in.gcount()) != into.size())
      throw IoError("cannot read " + name + ": it got shorter while being read");
  };
  std::string head;
  read(head, format == PointCacheFormat::Pc2 ? kPc2HeaderBytes : kMddHeaderBytes);
  if (format == PointCacheFormat::Pc2 || size < kMddHeaderBytes)
    return parse_point_cache_header(head, size, format, name);
  // MDD: the counts first (checked against the size), then the frame times.
  const PointCacheHeader counts = [&] {
    PointCacheHeader h;
    h.format = format;
    h.frames = count(load_i32(head.data(), true), "frame count", name);
    h.points = count(load_i32(head.data() + 4, true), "point count", name);
    h.data_offset = kMddHeaderBytes + 4 * uint64_t(h.frames);
    check_size(h, size, name);
    return h;
  }();
  std::string times;
  read(times, counts.data_offset - kMddHeaderBytes);
  return parse_point_cache_header(head + times, size, format, name);
}

std::string read_point_cache_frame_bytes(const fs::path& file, const PointCacheHeader& header,
                                         int frame) {
  if (frame < 0 || frame >= header.frames)
    throw std::out_of_range("read_point_cache_frame_bytes: frame " + std::to_string(frame));
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw IoError("cannot open '" + file.string() + "': " + std::strerror(errno ? errno : ENOENT));
  std::string bytes(size_t(header.frame_bytes()), '\0');
  in.seekg(std::streamoff(header.data_offset + uint64_t(frame) * header.frame_bytes()));
  in.read(bytes.data(), std::streamsize(bytes.size()));
  if (!in || uint64_t(in.gcount()) != bytes.size())
    throw IoError("cannot read frame " + std::to_string(frame) + " of '" + file.string() +
                  "': the file got shorter after its header was read");
  return bytes;
}

Positions decode_point_cache_frame(std::string_view bytes, const PointCacheHeader& header,
                                   int frame, const std::string& name) {
  if (bytes.size() != header.frame_bytes())
    throw std::logic_error("decode_point_cache_frame: wrong number of bytes");
  const bool big = big_endian(header.format);
  Positions V(header.points, 3);
  for (int v = 0; v < header.points; ++v) {
    for (int k = 0; k < 3; ++k) V(v, k) = load_f32(bytes.data() + 12 * size_t(v) + 4 * k, big);
    if (!V.row(v).allFinite())
      throw InputError(name + ": frame " + std::to_string(frame) + ", vertex " +
                       std::to_string(v) + ": non-finite position (" + number(V(v, 0)) + ", " +
                       number(V(v, 1)) + ", " + number(V(v, 2)) + ")");
    for (int k = 0; k < 3; ++k)
      if (std::fabs(V(v, k)) > kMaxCoordinate)  // as every mesh reader: io/obj.cpp, ply, off
        throw InputError(name + ": frame " + std::to_string(frame) + ", vertex " +
                         std::to_string(v) + ": coordinate " + "xyz"[k] + " " + number(V(v, k)) +
                         " is too large (more than 1e18 in magnitude: the geometry would "
                         "overflow)");
  }
  return V;
}

std::string format_point_cache_header(PointCacheFormat format, int points, int frames,
                                      const PointCacheTiming& timing) {
  const bool big = big_endian(format);
  std::string out;
  if (format == PointCacheFormat::Pc2) {
    out.append(kPc2Magic, sizeof kPc2Magic);
    store_i32(out, 1, big);
    store_i32(out, points, big);
    store_f32(out, timing.start, big);
    store_f32(out, timing.sample_rate, big);
    store_i32(out, frames, big);
    return out;
  }
  if (timing.times.size() != size_t(frames))
    throw std::logic_error("format_point_cache_header: an MDD needs one time per frame");
  store_i32(out, frames, big);
  store_i32(out, points, big);
  for (float t : timing.times) store_f32(out, t, big);
  return out;
}

std::string format_point_cache_frame(PointCacheFormat format, const Positions& V,
                                     const std::string& what) {
  const bool big = big_endian(format);
  std::string out;
  out.reserve(size_t(V.rows()) * 12);
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double x = V(v, k);
      if (!std::isfinite(x) || std::fabs(x) > double(FLT_MAX))
        throw InputError(what + ", vertex " + std::to_string(v) + ": position (" +
                         number(V(v, 0)) + ", " + number(V(v, 1)) + ", " + number(V(v, 2)) +
                         ") is not finite in float32");
      store_f32(out, static_cast<float>(x), big);
    }
  }
  return out;
}

void write_point_cache(const fs::path& path, PointCacheFormat format, int points, int frames,
                       const PointCacheTiming& timing,
                       const std::function<Positions(int)>& frame) {
  // What the reader refuses is never written: a header the program cannot read back.
  const std::string name = "'" + path.string() + "'";
  if (format == PointCacheFormat::Pc2)
    if (const std::string problem = pc2_timing_problem(timing.start, timing.sample_rate, frames);
        !problem.empty())
      throw InputError(name + ": cannot be written, its reader would refuse it: its " + problem);
  for (size_t f = 0; f < timing.times.size(); ++f)
    if (!std::isfinite(timing.times[f]))
      throw InputError(name + ": frame " + std::to_string(f) + ": the frame time " +
                       number(timing.times[f]) + " cannot be written (MDD times are finite)");
  AtomicFileWriter file(path);
  file.write(format_point_cache_header(format, points, frames, timing));
  for (int f = 0; f < frames; ++f) {
    const Positions V = frame(f);
    const std::string what = "'" + path.string() + "': frame " + std::to_string(f);
    if (V.rows() != points)
      throw InputError(what + ": " + std::to_string(V.rows()) + " vertices, but the cache has " +
                       std::to_string(points));
    file.write(format_point_cache_frame(format, V, what));
  }
  file.commit();
}

}  // namespace sm
