// The PNG writer: checksums against published values, and every image decoded back by a small
// independent reader (chunks and their CRCs, the zlib header, stored deflate blocks, Adler-32,
// filter 0) to the same pixels.
#include <catch2/catch.hpp>

#include "io/png.hpp"
#include "mesh/errors.hpp"

using namespace sm;

namespace {

uint32_t be32(const std::string& s, size_t at) {
  REQUIRE(at + 4 <= s.size());
  uint32_t x = 0;
  for (size_t i = 0; i < 4; ++i) x = (x << 8) | uint8_t(s[at + i]);
  return x;
}

// Inflates a zlib stream made of stored blocks only (what the writer produces); fails the test
// on anything else.
std::string inflate_stored(const std::string& z) {
  REQUIRE(z.size() >= 6);
  const uint8_t cmf = uint8_t(z[0]), flg = uint8_t(z[1]);
  CHECK((cmf & 0x0f) == 8);             // deflate
  CHECK(((cmf << 8) | flg) % 31 == 0);  // header check bits
  CHECK((flg & 0x20) == 0);             // no preset dictionary
  std::string out;
  size_t at = 2;
  for (bool last = false; !last;) {
    REQUIRE(at + 5 <= z.size());
    const uint8_t head = uint8_t(z[at]);
    last = head & 1;
    REQUIRE(((head >> 1) & 3) == 0);  // BTYPE 00: stored (the writer's bits 3..7 are 0 too)
    const uint16_t len = uint16_t(uint8_t(z[at + 1]) | (uint8_t(z[at + 2]) << 8));
    const uint16_t nlen = uint16_t(uint8_t(z[at + 3]) | (uint8_t(z[at + 4]) << 8));
    REQUIRE(uint16_t(~len) == nlen);
    at += 5;
    REQUIRE(at + len <= z.size());
    out.append(z, at, len);
    at += len;
  }
  REQUIRE(at + 4 == z.size());
  CHECK(be32(z, at) == adler32(out));
  return out;
}

struct Decoded {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
};

Decoded decode_png(const std::string& png) {
  REQUIRE(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  Decoded d;
  std::string idat;
  size_t at = 8;
  std::vector<std::string> types;
  while (at < png.size()) {
    const uint32_t length = be32(png, at);
    REQUIRE(at + 12 + length <= png.size());
    const std::string type = png.substr(at + 4, 4);
    const std::string data = png.substr(at + 8, length);
    CHECK(be32(png, at + 8 + length) == crc32(png.substr(at + 4, 4 + length)));
    types.push_back(type);
    if (type == "IHDR") {
      REQUIRE(length == 13);
      d.width = int(be32(data, 0));
      d.height = int(be32(data, 4));
      CHECK(uint8_t(data[8]) == 8);
      const int colour = uint8_t(data[9]);
      d.channels = colour == 0 ? 1 : colour == 2 ? 3 : colour == 6 ? 4 : 0;
      CHECK(data.substr(10) == std::string(3, '\0'));
    } else if (type == "IDAT") {
      idat += data;
    }
    at += 12 + length;
  }
  REQUIRE(types.size() >= 3);
  CHECK(types.front() == "IHDR");
  CHECK(types.back() == "IEND");
  const std::string raw = inflate_stored(idat);
  const size_t row = size_t(d.width) * size_t(d.channels);
  REQUIRE(raw.size() == (row + 1) * size_t(d.height));
  for (int y = 0; y < d.height; ++y) {
    CHECK(raw[size_t(y) * (row + 1)] == '\0');  // filter 0
    const auto* first = reinterpret_cast<const uint8_t*>(raw.data()) + size_t(y) * (row + 1) + 1;
    d.pixels.insert(d.pixels.end(), first, first + row);
  }
  return d;
}

Image8 pattern(int width, int height, int channels) {
  Image8 image{width, height, channels, {}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c)
        image.pixels.push_back(uint8_t((x * 7 + y * 13 + c * 101 + x * y) & 0xff));
  return image;
}

}  // namespace

TEST_CASE("CRC-32 and Adler-32 give the published check values") {
  CHECK(crc32("123456789") == 0xCBF43926u);
  CHECK(crc32("") == 0u);
  CHECK(crc32("6789", crc32("12345")) == 0xCBF43926u);  // continued
  CHECK(crc32("IEND") == 0xAE426082u);                  // the CRC every PNG ends with
  CHECK(adler32("Wikipedia") == 0x11E60398u);
  CHECK(adler32("") == 1u);
  // Long input: the sums are reduced often enough not to overflow.
  const std::string ones(100000, '\xff');
  uint64_t a = 1, b = 0;
  for (const char c : ones) {
    a = (a + uint8_t(c)) % 65521;
    b = (b + a) % 65521;
  }
  CHECK(adler32(ones) == uint32_t((b << 16) | a));
}

TEST_CASE("zlib streams of stored blocks inflate back, across block boundaries") {
  for (const size_t n : {size_t(0), size_t(1), size_t(65535), size_t(65536), size_t(200000)}) {
    std::string data(n, '\0');
    for (size_t i = 0; i < n; ++i) data[i] = char((i * 31 + i / 7) & 0xff);
    const std::string z = zlib_stored(data);
    CHECK(z.size() == data.size() + 6 + 5 * std::max<size_t>(1, (n + 65534) / 65535));
    CHECK(inflate_stored(z) == data);
  }
}

TEST_CASE("PNG images decode back to their pixels") {
  for (const int channels : {1, 3, 4}) {
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{1, 1}, {5, 3}, {300, 250}}) {
      INFO(w << "x" << h << "x" << channels);
      const Image8 image = pattern(w, h, channels);
      const std::string png = encode_png(image);
      const Decoded d = decode_png(png);
      CHECK(d.width == w);
      CHECK(d.height == h);
      CHECK(d.channels == channels);
      CHECK(d.pixels == image.pixels);
      CHECK(encode_png(image) == png);  // deterministic
    }
  }
}

TEST_CASE("PNG images larger than one IDAT chunk are split and still decode") {
  const Image8 image = pattern(700, 600, 3);  // 1.26 MB of pixels: two IDAT chunks
  const std::string png = encode_png(image);
  CHECK(png.find("IDAT") != png.rfind("IDAT"));
  CHECK(decode_png(png).pixels == image.pixels);
}

TEST_CASE("PNG refuses impossible images") {
  CHECK_THROWS_AS(encode_png(Image8{0, 4, 3, {}}), InputError);
  CHECK_THROWS_AS(encode_png(Image8{70000, 1, 1, std::vector<uint8_t>(70000)}), InputError);
  CHECK_THROWS_WITH(encode_png(Image8{2, 2, 2, std::vector<uint8_t>(8)}),
                    Catch::Contains("2 channels"));
  CHECK_THROWS_WITH(encode_png(Image8{2, 2, 3, std::vector<uint8_t>(11)}),
                    Catch::Contains("11 bytes of pixels for 2x2x3"));
}
