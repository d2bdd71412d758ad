// PC2 and MDD point caches: headers checked against the file size (truncated files, lying
// counts, wrong magic or version) with messages that name the file; frames read by offset;
// whole caches written atomically and read back bit for bit (as float32).
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/point_cache.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using sm::test::error_of;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// Frame f of a small moving triangle fan, positions exact in float32.
Positions frame_positions(int f, int points = 5) {
  Positions V(points, 3);
  for (int v = 0; v < points; ++v)
    V.row(v) << 0.25 * v + 0.5 * f, -1.5 + 0.125 * f * v, std::ldexp(double(v * 3 + f), -4);
  return V;
}

fs::path write_cache(const fs::path& file, PointCacheFormat format, int frames, int points = 5) {
  PointCacheTiming t;
  t.start = 3;
  t.sample_rate = 0.5f;
  for (int f = 0; f < frames; ++f) t.times.push_back(float(f) / 24.0f);
  write_point_cache(file, format, points, frames, t,
                    [&](int f) { return frame_positions(f, points); });
  return file;
}

void put_i32_le(std::string& s, size_t at, int32_t value) {
  std::memcpy(&s[at], &value, 4);  // a little-endian machine, like PC2
}

void put_i32_be(std::string& s, size_t at, int32_t value) {
  const uint32_t u = uint32_t(value);
  for (int i = 0; i < 4; ++i) s[at + size_t(i)] = char((u >> (24 - 8 * i)) & 0xff);
}

std::string header_error(const std::string& bytes, PointCacheFormat format) {
  return error_of<InputError>(
      [&] { parse_point_cache_header(bytes, bytes.size(), format, "'c'"); });
}

}  // namespace

TEST_CASE("a PC2 cache is written and read back: header, frames by offset, float32 positions") {
  test::TempDir dir("pc2_roundtrip");
  const fs::path file = write_cache(dir / "take.pc2", PointCacheFormat::Pc2, 4);
  const std::string bytes = read_file(file);
  REQUIRE(bytes.size() == 32 + 4 * 5 * 12);
  CHECK(bytes.compare(0, 12, std::string("POINTCACHE2\0", 12)) == 0);
  const PointCacheHeader h = read_point_cache_header(file, PointCacheFormat::Pc2);
  CHECK(h.points == 5);
  CHECK(h.frames == 4);
  CHECK(h.start == 3.0f);
  CHECK(h.sample_rate == 0.5f);
  CHECK(h.data_offset == 32);
  CHECK(h.times.empty());
  for (int f : {2, 0, 3}) {
    const Positions V =
        decode_point_cache_frame(read_point_cache_frame_bytes(file, h, f), h, f, "take.pc2");
    CHECK(V == frame_positions(f));
  }
}

TEST_CASE("an MDD cache is big-endian, with frame times") {
  test::TempDir dir("mdd_roundtrip");
  const fs::path file = write_cache(dir / "take.mdd", PointCacheFormat::Mdd, 3);
  const std::string bytes = read_file(file);
  REQUIRE(bytes.size() == 8 + 3 * 4 + 3 * 5 * 12);
  CHECK(bytes.substr(0, 8) == std::string("\0\0\0\3\0\0\0\5", 8));
  const PointCacheHeader h = read_point_cache_header(file, PointCacheFormat::Mdd);
  CHECK(h.frames == 3);
  CHECK(h.points == 5);
  CHECK(h.times == std::vector<float>{0.0f, 1.0f / 24, 2.0f / 24});
  CHECK(h.data_offset == 20);
  const Positions V =
      decode_point_cache_frame(read_point_cache_frame_bytes(file, h, 2), h, 2, "take.mdd");
  CHECK(V == frame_positions(2));
}

TEST_CASE("positions are rounded to the nearest float32") {
  Positions V(1, 3);
  V << 0.1, 1.0 / 3.0, -2e-9;
  const std::string bytes = format_point_cache_frame(PointCacheFormat::Pc2, V, "f");
  PointCacheHeader h;
  h.points = 1;
  h.frames = 1;
  const Positions back = decode_point_cache_frame(bytes, h, 0, "f");
  for (int k = 0; k < 3; ++k) CHECK(back(0, k) == double(float(V(0, k))));
  V(0, 1) = 1e39;  // beyond float32
  CHECK_THAT(error_of<InputError>([&] { format_point_cache_frame(PointCacheFormat::Mdd, V, "f 3"); }),
             Contains("f 3, vertex 0: position (0.1, 1e+39, -2e-09)") &&
                 Contains("is not finite in float32"));
}

TEST_CASE("a PC2 header is checked against the file size before anything is allocated") {
  test::TempDir dir("pc2_bad");
  const std::string good = read_file(write_cache(dir / "a.pc2", PointCacheFormat::Pc2, 2));
  const auto P = PointCacheFormat::Pc2;

  std::string bad = good;
  bad[0] = 'X';
  CHECK(header_error(bad, P) == "'c': not a PC2 file (it does not start with \"POINTCACHE2\\0\")");
  bad = good;
  put_i32_le(bad, 12, 2);
  CHECK(header_error(bad, P) == "'c': PC2 version 2 (only 1 is known)");
  CHECK(header_error(good.substr(0, 20), P) == "'c': 20 bytes, too short for a PC2 header (32 bytes)");
  CHECK(header_error(good.substr(0, good.size() - 1), P) ==
        "'c': truncated: 151 bytes, but the header's 2 frames of 5 points need 152");
  CHECK(header_error(good + "x", P) ==
        "'c': 153 bytes, but the header's 2 frames of 5 points need 152 (trailing bytes, or wrong "
        "counts)");
  bad = good;
  put_i32_le(bad, 16, 0x7fffffff);  // a hostile point count: refused, nothing allocated
  CHECK_THAT(header_error(bad, P), Contains("truncated: 152 bytes, but the header's 2 frames of "
                                            "2147483647 points need 51539607560"));
  bad = good;
  put_i32_le(bad, 28, 0x7fffffff);
  put_i32_le(bad, 16, 0x7fffffff);
  CHECK(header_error(bad, P) == "'c': truncated: 152 bytes, but the header's 2147483647 frames of "
                                "2147483647 points need 55340232169589047340");
  bad = good;
  put_i32_le(bad, 28, -4);
  CHECK(header_error(bad, P) == "'c': the header's sample count is -4 (expected at least 1)");
  bad = good;
  put_i32_le(bad, 16, 0);
  CHECK(header_error(bad, P) == "'c': the header's point count is 0 (expected at least 1)");
  bad = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bad[24], &nan, 4);
  CHECK_THAT(header_error(bad, P), Contains("sample rate (nan) is not finite"));
}

TEST_CASE("an MDD header is checked against the file size, its times for finite values") {
  test::TempDir dir("mdd_bad");
  const fs::path file = write_cache(dir / "a.mdd", PointCacheFormat::Mdd, 2);
  const std::string good = read_file(file);
  const auto M = PointCacheFormat::Mdd;
  CHECK(header_error(good.substr(0, 5), M) == "'c': 5 bytes, too short for a MDD header (8 bytes)");
  CHECK(header_error(good.substr(0, good.size() - 12), M) ==
        "'c': truncated: 124 bytes, but the header's 2 frames of 5 points need 136");
  std::string bad = good;
  put_i32_be(bad, 0, 0x7fffffff);  // a hostile frame count: the times are not allocated
  CHECK(header_error(bad, M) ==
        "'c': 136 bytes, too short for the header (8589934596 bytes for 2147483647 frames of 5 "
        "points)");
  bad = good;
  put_i32_be(bad, 4, 6);  // lying point count
  CHECK(header_error(bad, M) ==
        "'c': truncated: 136 bytes, but the header's 2 frames of 6 points need 160");
  bad = good;
  put_i32_be(bad, 0, -1);
  CHECK(header_error(bad, M) == "'c': the header's frame count is -1 (expected at least 1)");
  bad = good;
  bad[12] = char(0x7f);  // frame 1's time: 0x7f80.... is infinity
  bad[13] = char(0x80);
  bad[14] = bad[15] = 0;
  CHECK(header_error(bad, M) == "'c': frame 1: non-finite frame time inf");

  // The same checks reading the file (the header and times only are read).
  write_file_atomic(dir / "lying.mdd", bad.substr(0, 8) + std::string(4, '\0'));
  const std::string read_lying = error_of<InputError>(
      [&] { read_point_cache_header(dir / "lying.mdd", PointCacheFormat::Mdd); });
  CHECK_THAT(read_lying, Contains("lying.mdd': 12 bytes, too short for the header (16 bytes for 2 frames of 5 "
                                   "points)"));
}

TEST_CASE("a non-finite position names the file, frame and vertex") {
  test::TempDir dir("pc2_nan");
  std::string bytes = read_file(write_cache(dir / "a.pc2", PointCacheFormat::Pc2, 3));
  const float inf = std::numeric_limits<float>::infinity();
  std::memcpy(&bytes[32 + 2 * 60 + 3 * 12 + 4], &inf, 4);  // frame 2, vertex 3, y
  write_file_atomic(dir / "a.pc2", bytes);
  const PointCacheHeader h = read_point_cache_header(dir / "a.pc2", PointCacheFormat::Pc2);
  CHECK_NOTHROW(decode_point_cache_frame(read_point_cache_frame_bytes(dir / "a.pc2", h, 1), h, 1,
                                         "'a.pc2'"));
  CHECK(error_of<InputError>([&] {
          decode_point_cache_frame(read_point_cache_frame_bytes(dir / "a.pc2", h, 2), h, 2,
                                   "'a.pc2'");
        }) == "'a.pc2': frame 2, vertex 3: non-finite position (1.75, inf, 0.6875)");
}

TEST_CASE("only regular files are opened as caches") {
  test::TempDir dir("pc2_special");
  fs::create_directories(dir / "folder.pc2");
  CHECK_THAT(error_of<InputError>(
                 [&] { read_point_cache_header(dir / "folder.pc2", PointCacheFormat::Pc2); }),
             Contains("folder.pc2': not a regular file"));
  REQUIRE(::mkfifo((dir / "pipe.pc2").c_str(), 0600) == 0);  // would block a reader forever
  CHECK_THAT(error_of<InputError>(
                 [&] { read_point_cache_header(dir / "pipe.pc2", PointCacheFormat::Pc2); }),
             Contains("pipe.pc2': not a regular file"));
  CHECK_THAT(error_of<IoError>(
                 [&] { read_point_cache_header(dir / "missing.pc2", PointCacheFormat::Pc2); }),
             Contains("cannot open '") && Contains("missing.pc2': No such file or directory"));
}

TEST_CASE("a cache whose frame cannot be given leaves no file behind") {
  test::TempDir dir("pc2_atomic");
  const fs::path file = write_cache(dir / "keep.pc2", PointCacheFormat::Pc2, 2);
  const std::string before = read_file(file);
  CHECK_THROWS_AS(write_point_cache(file, PointCacheFormat::Pc2, 5, 3, {},
                                    [&](int f) -> Positions {
                                      if (f == 2) throw IoError("frame 2 is gone");
                                      return frame_positions(f);
                                    }),
                  IoError);
  CHECK(read_file(file) == before);
  CHECK_THAT(error_of<InputError>([&] {
               write_point_cache(file, PointCacheFormat::Pc2, 5, 1, {},
                                 [&](int) { return frame_positions(0, 4); });
             }),
             Contains("frame 0: 4 vertices, but the cache has 5"));
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) files += entry.is_regular_file();
  CHECK(files == 1);
}
