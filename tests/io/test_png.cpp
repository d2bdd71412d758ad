// The PNG writer: every image read back chunk by chunk (each chunk's CRC-32, the zlib header and
// Adler-32 of the inflated scanlines, their filter bytes) and decoded by stb_image, an independent
// decoder, to the same pixels; deterministic bytes; impossible images refused.
#include <catch2/catch.hpp>
#include <stb_image.h>

#include <array>
#include <memory>

#include "io/png.hpp"
#include "core/errors.hpp"

using namespace sm;

namespace {

// CRC-32 (ISO 3309, as PNG chunks use) and Adler-32 (RFC 1950), written out here to check the
// encoder's output with code it does not share.
uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (const char ch : bytes) {
    c ^= uint8_t(ch);
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

uint32_t adler32(const std::string& bytes) {
  uint32_t a = 1, b = 0;
  for (const char ch : bytes) {
    a = (a + uint8_t(ch)) % 65521;
    b = (b + a) % 65521;
  }
  return (b << 16) | a;
}

uint32_t be32(const std::string& s, size_t at) {
  REQUIRE(at + 4 <= s.size());
  uint32_t x = 0;
  for (size_t i = 0; i < 4; ++i) x = (x << 8) | uint8_t(s[at + i]);
  return x;
}

struct Decoded {
  int width = 0, height = 0, channels = 0;
  std::vector<uint8_t> pixels;
};

// The chunks (IHDR first, IEND last, every CRC right), the zlib stream of the IDAT chunks (header,
// the scanlines' filter bytes 0 to 4, Adler-32), then the pixels as stb_image decodes them.
Decoded decode_png(const std::string& png) {
  REQUIRE(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  Decoded d;
  std::string idat;
  std::vector<std::string> types;
  for (size_t at = 8; at < png.size();) {
    const uint32_t length = be32(png, at);
    REQUIRE(at + 12 + length <= png.size());
    const std::string type = png.substr(at + 4, 4), data = png.substr(at + 8, length);
    CHECK(be32(png, at + 8 + length) == crc32(png.substr(at + 4, 4 + length)));
    types.push_back(type);
    if (type == "IHDR") {
      REQUIRE(length == 13);
      d.width = int(be32(data, 0));
      d.height = int(be32(data, 4));
      CHECK(uint8_t(data[8]) == 8);  // bit depth
      const int colour = uint8_t(data[9]);
      d.channels = colour == 0 ? 1 : colour == 2 ? 3 : colour == 6 ? 4 : 0;
      CHECK(data.substr(10) == std::string(3, '\0'));  // deflate, standard filters, no interlace
    } else if (type == "IDAT") {
      idat += data;
    }
    at += 12 + length;
  }
  REQUIRE(types.size() >= 3);
  CHECK(types.front() == "IHDR");
  CHECK(types.back() == "IEND");

  REQUIRE(idat.size() >= 6);
  CHECK((uint8_t(idat[0]) & 0x0f) == 8);                             // deflate
  CHECK(((uint8_t(idat[0]) << 8) | uint8_t(idat[1])) % 31 == 0);     // header check bits
  CHECK((uint8_t(idat[1]) & 0x20) == 0);                             // no preset dictionary
  int size = 0;
  const std::unique_ptr<char, void (*)(void*)> inflated(
      stbi_zlib_decode_malloc(idat.data(), int(idat.size()), &size), stbi_image_free);
  REQUIRE(inflated);
  const std::string raw(inflated.get(), size_t(size));
  CHECK(be32(idat, idat.size() - 4) == adler32(raw));
  const size_t row = size_t(d.width) * size_t(d.channels);
  REQUIRE(raw.size() == (row + 1) * size_t(d.height));
  for (int y = 0; y < d.height; ++y) CHECK(uint8_t(raw[size_t(y) * (row + 1)]) <= 4);

  int width = 0, height = 0, channels = 0;
  const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()), int(png.size()), &width,
                            &height, &channels, 0),
      stbi_image_free);
  REQUIRE(pixels);
  CHECK(width == d.width);
  CHECK(height == d.height);
  CHECK(channels == d.channels);
  d.pixels.assign(pixels.get(), pixels.get() + row * size_t(d.height));
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

TEST_CASE("the test's CRC-32 and Adler-32 give the published check values") {
  CHECK(crc32("123456789") == 0xCBF43926u);
  CHECK(crc32("") == 0u);
  CHECK(crc32("IEND") == 0xAE426082u);  // the CRC every PNG ends with
  CHECK(adler32("Wikipedia") == 0x11E60398u);
  CHECK(adler32("") == 1u);
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

TEST_CASE("PNG images of noise (incompressible) and of flat colour still decode") {
  Image8 noise{700, 600, 3, std::vector<uint8_t>(700 * 600 * 3)};
  uint32_t state = 12345;
  for (uint8_t& p : noise.pixels) p = uint8_t((state = state * 1664525u + 1013904223u) >> 24);
  const std::string png = encode_png(noise);
  CHECK(decode_png(png).pixels == noise.pixels);
  const Image8 flat{640, 480, 4, std::vector<uint8_t>(640 * 480 * 4, 200)};
  const std::string small = encode_png(flat);
  CHECK(decode_png(small).pixels == flat.pixels);
  CHECK(small.size() < flat.pixels.size() / 50);  // compressed (stb: about 1/100)
}

TEST_CASE("PNG refuses impossible images") {
  CHECK_THROWS_AS(encode_png(Image8{0, 4, 3, {}}), InputError);
  CHECK_THROWS_AS(encode_png(Image8{70000, 1, 1, std::vector<uint8_t>(70000)}), InputError);
  CHECK_THROWS_WITH(encode_png(Image8{2, 2, 2, std::vector<uint8_t>(8)}),
                    Catch::Contains("2 channels"));
  CHECK_THROWS_WITH(encode_png(Image8{2, 2, 3, std::vector<uint8_t>(11)}),
                    Catch::Contains("11 bytes of pixels for 2x2x3"));
  // Beyond what stb_image_write can count, checked before the pixels: no 300 MB buffer needed.
  CHECK_THROWS_WITH(encode_png(Image8{20000, 5000, 3, {}}),
                    Catch::Contains("20000x5000x3 is more than 256 MiB of pixels"));
}
