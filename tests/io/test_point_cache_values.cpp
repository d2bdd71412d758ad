// Point-cache values under the limits of every other reader (issue 24.4): coordinates beyond 1e18
// (kMaxCoordinate, as OBJ, PLY, OFF and glTF), a PC2 start frame or sample rate that would make a
// written header unreadable, a sample rate <= 0; and nothing written that the reader refuses.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/point_cache.hpp"
#include "io/point_cache_timing.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using sm::test::error_of;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

Positions small_frame(int f) {
  Positions V(4, 3);
  for (int v = 0; v < 4; ++v) V.row(v) << 0.5 * v, 0.25 * f, -1.0 + v;
  return V;
}

// The bytes of a PC2 cache of 3 frames of 4 points (start 0, rate 1), as written by the library.
std::string pc2_bytes(const fs::path& dir) {
  write_point_cache(dir / "ok.pc2", PointCacheFormat::Pc2, 4, 3, {}, small_frame);
  return read_file(dir / "ok.pc2");
}

void put_f32_le(std::string& s, size_t at, float value) {
  std::memcpy(&s[at], &value, 4);  // a little-endian machine, like PC2
}

void put_f32_be(std::string& s, size_t at, float value) {
  uint32_t u;
  std::memcpy(&u, &value, 4);
  for (int i = 0; i < 4; ++i) s[at + size_t(i)] = char((u >> (24 - 8 * i)) & 0xff);
}

std::string header_error(const std::string& bytes) {
  return error_of<InputError>([&] {
    parse_point_cache_header(bytes, bytes.size(), PointCacheFormat::Pc2, "'c.pc2'");
  });
}

std::string frame_error(const std::string& bytes, PointCacheFormat format, int frame) {
  const PointCacheHeader h = parse_point_cache_header(bytes, bytes.size(), format, "'c'");
  const std::string data = bytes.substr(size_t(h.data_offset + frame * h.frame_bytes()),
                                        size_t(h.frame_bytes()));
  return error_of<InputError>([&] { decode_point_cache_frame(data, h, frame, "'c'"); });
}

int files_in(const fs::path& dir) {
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) n += entry.is_regular_file() ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("a point-cache coordinate beyond 1e18 is refused like an OBJ's, naming frame and vertex") {
  test::TempDir dir("pc_coordinate_limit");
  std::string pc2 = pc2_bytes(dir.path());
  put_f32_le(pc2, 32 + 2 * 48 + 3 * 12 + 4, 1e30f);  // frame 2, vertex 3, y
  CHECK(frame_error(pc2, PointCacheFormat::Pc2, 1).empty());
  CHECK(frame_error(pc2, PointCacheFormat::Pc2, 2) ==
        "'c': frame 2, vertex 3: coordinate y 1.00000002e+30 is too large (more than 1e18 in "
        "magnitude: the geometry would overflow)");
  // The largest float32 values at and below the limit are kept: 1e18 is not a float32, its
  // nearest one (999999984306749440) is below it; the next float32 up is beyond it.
  const float at_limit = 1e18f;
  REQUIRE(double(at_limit) < 1e18);
  put_f32_le(pc2, 32 + 2 * 48 + 3 * 12 + 4, -at_limit);
  CHECK(frame_error(pc2, PointCacheFormat::Pc2, 2).empty());
  put_f32_le(pc2, 32 + 2 * 48 + 3 * 12 + 4,
             -std::nextafter(at_limit, std::numeric_limits<float>::infinity()));
  CHECK_THAT(frame_error(pc2, PointCacheFormat::Pc2, 2),
             Contains("vertex 3: coordinate y -1.00000005e+18 is too large"));

  // MDD (big-endian): frame 0, vertex 0, x.
  write_point_cache(dir / "ok.mdd", PointCacheFormat::Mdd, 4, 2, {0, 1, {0.0f, 0.5f}},
                    small_frame);
  std::string mdd = read_file(dir / "ok.mdd");
  put_f32_be(mdd, 8 + 2 * 4, -3e38f);
  CHECK(frame_error(mdd, PointCacheFormat::Mdd, 0) ==
        "'c': frame 0, vertex 0: coordinate x -3.00000001e+38 is too large (more than 1e18 in "
        "magnitude: the geometry would overflow)");
}

TEST_CASE("a PC2 start frame or sample rate that no header could hold again is refused") {
  test::TempDir dir("pc_timing_limit");
  const std::string good = pc2_bytes(dir.path());  // 3 samples
  CHECK(header_error(good).empty());
  std::string bad = good;
  put_f32_le(bad, 20, 3e38f);  // start frame: finite, but start + rate would not be in float32
  CHECK(header_error(bad) ==
        "'c.pc2': the header's frames run from 3.00000001e+38 to 3.00000001e+38 (start frame + "
        "(samples - 1) x sample rate), beyond 1e18 in magnitude");
  bad = good;
  put_f32_le(bad, 24, 3e38f);  // the third sample's frame, 6e38, is not a float32
  CHECK(header_error(bad) ==
        "'c.pc2': the header's frames run from 0 to 6.00000001e+38 (start frame + (samples - 1) "
        "x sample rate), beyond 1e18 in magnitude");
  for (const float rate : {0.0f, -0.0f, -1.0f, -std::numeric_limits<float>::denorm_min()}) {
    bad = good;
    put_f32_le(bad, 24, rate);
    CHECK_THAT(header_error(bad),
               Contains("'c.pc2': the header's sample rate ") &&
                   Contains(" is not positive (it is the number of frames from one sample to "
                            "the next)"));
  }
  // Within the limits: accepted. Frames -1e18, 0 and 1e18 (as float32 values, just below).
  bad = good;
  put_f32_le(bad, 20, -1e18f);
  put_f32_le(bad, 24, 1e18f);
  CHECK(header_error(bad).empty());
  put_f32_le(bad, 24, std::numeric_limits<float>::denorm_min());
  CHECK(header_error(bad).empty());
  // One sample has one frame number whatever the rate.
  CHECK(pc2_timing_problem(0.0f, 3e38f, 1).empty());
  CHECK_FALSE(pc2_timing_problem(0.0f, 3e38f, 2).empty());
  CHECK_FALSE(pc2_timing_problem(1.5e18f, 1.0f, 1).empty());
}

TEST_CASE("a point cache is never written with a header its reader refuses") {
  test::TempDir dir("pc_write_limit");
  const fs::path file = dir / "keep.pc2";
  write_point_cache(file, PointCacheFormat::Pc2, 4, 3, {}, small_frame);
  const std::string before = read_file(file);
  const float inf = std::numeric_limits<float>::infinity();
  int asked = 0;
  const auto frame = [&](int f) {
    ++asked;
    return small_frame(f);
  };
  CHECK(error_of<InputError>([&] {
          write_point_cache(file, PointCacheFormat::Pc2, 4, 3, {inf, 1, {}}, frame);
        }) == "'" + file.string() +
                  "': cannot be written, its reader would refuse it: its start frame (inf) or "
                  "sample rate (1) is not finite");
  CHECK(error_of<InputError>([&] {
          write_point_cache(file, PointCacheFormat::Pc2, 4, 3, {0, 0, {}}, frame);
        }) == "'" + file.string() +
                  "': cannot be written, its reader would refuse it: its sample rate 0 is not "
                  "positive (it is the number of frames from one sample to the next)");
  CHECK(error_of<InputError>([&] {
          write_point_cache(dir / "t.mdd", PointCacheFormat::Mdd, 4, 2, {0, 1, {0.0f, inf}},
                            frame);
        }) == "'" + (dir / "t.mdd").string() +
                  "': frame 1: the frame time inf cannot be written (MDD times are finite)");
  CHECK(asked == 0);  // refused before any frame was asked for
  CHECK(read_file(file) == before);
  CHECK(files_in(dir.path()) == 1);  // no temporary left, no t.mdd
  // What is written reads back.
  write_point_cache(file, PointCacheFormat::Pc2, 4, 3, {-1e18f, 1e18f, {}}, frame);
  const PointCacheHeader h = read_point_cache_header(file, PointCacheFormat::Pc2);
  CHECK(h.start == -1e18f);
  CHECK(h.sample_rate == 1e18f);
}
