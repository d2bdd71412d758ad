#include "io/png.hpp"

#include <algorithm>
#include <array>

#include "io/atomic_file.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace {

std::array<uint32_t, 256> make_crc_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t n = 0; n < 256; ++n) {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

void append_be32(std::string& out, uint32_t x) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((x >> shift) & 0xffu);
}

// length, type, data, CRC of type and data
void append_chunk(std::string& out, const char (&type)[5], std::string_view data) {
  append_be32(out, static_cast<uint32_t>(data.size()));
  const size_t start = out.size();
  out.append(type, 4);
  out.append(data);
  append_be32(out, crc32(std::string_view(out).substr(start)));
}

}  // namespace

uint32_t crc32(std::string_view bytes, uint32_t crc) {
  static const std::array<uint32_t, 256> table = make_crc_table();
  uint32_t c = crc ^ 0xffffffffu;
  for (const char ch : bytes) c = table[(c ^ static_cast<uint8_t>(ch)) & 0xffu] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

uint32_t adler32(std::string_view bytes) {
  constexpr uint32_t kMod = 65521;
  uint32_t a = 1, b = 0;
  size_t i = 0;
  while (i < bytes.size()) {
    // 5552 bytes keep b below 2^32 before the modulo (zlib's NMAX)
    const size_t end = std::min(bytes.size(), i + 5552);
    for (; i < end; ++i) {
      a += static_cast<uint8_t>(bytes[i]);
      b += a;
    }
    a %= kMod;
    b %= kMod;
  }
  return (b << 16) | a;
}

std::string zlib_stored(std::string_view data) {
  constexpr size_t kBlock = 65535;
  std::string out;
  out.reserve(data.size() + 6 + 5 * (data.size() / kBlock + 1));
  out += '\x78';  // CMF: deflate, 32 KB window
  out += '\x01';  // FLG: no dictionary, fastest; (0x78 * 256 + 0x01) % 31 == 0
  size_t at = 0;
  do {
    const size_t n = std::min(kBlock, data.size() - at);
    const bool last = at + n == data.size();
    out += static_cast<char>(last ? 1 : 0);  // BFINAL, BTYPE 00 (stored)
    out += static_cast<char>(n & 0xffu);     // LEN, little-endian
    out += static_cast<char>(n >> 8);
    out += static_cast<char>(~n & 0xffu);  // NLEN = ~LEN
    out += static_cast<char>((~n >> 8) & 0xffu);
    out.append(data.substr(at, n));
    at += n;
  } while (at < data.size());
  append_be32(out, adler32(data));
  return out;
}

std::string encode_png(const Image8& image) {
  if (image.width < 1 || image.width > 65535 || image.height < 1 || image.height > 65535)
    throw InputError("cannot write PNG: size " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " is outside 1 to 65535 pixels per side");
  static const std::array<uint8_t, 5> kColourType = {0, 0, 0, 2, 6};  // by channel count
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    throw InputError("cannot write PNG: " + std::to_string(image.channels) +
                     " channels (1, 3 or 4 are written)");
  const size_t row = size_t(image.width) * size_t(image.channels);
  if (image.pixels.size() != row * size_t(image.height))
    throw InputError("cannot write PNG: " + std::to_string(image.pixels.size()) +
                     " bytes of pixels for " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + "x" + std::to_string(image.channels));

  std::string header;
  append_be32(header, uint32_t(image.width));
  append_be32(header, uint32_t(image.height));
  header += '\x08';                                          // bit depth
  header += static_cast<char>(kColourType[image.channels]);  // grey, RGB or RGBA
  header += std::string(3, '\0');  // deflate, adaptive filtering, no interlace

  std::string raw;
  raw.reserve((row + 1) * size_t(image.height));
  for (int y = 0; y < image.height; ++y) {
    raw += '\0';  // filter type 0: the row as is
    raw.append(reinterpret_cast<const char*>(image.pixels.data()) + size_t(y) * row, row);
  }

  std::string out = "\x89PNG\r\n\x1a\n";
  append_chunk(out, "IHDR", header);
  const std::string stream = zlib_stored(raw);
  constexpr size_t kIdat = size_t(1) << 20;  // several IDAT chunks: a chunk holds < 2^31 bytes
  for (size_t at = 0; at < stream.size(); at += kIdat)
    append_chunk(out, "IDAT", std::string_view(stream).substr(at, kIdat));
  append_chunk(out, "IEND", {});
  return out;
}

void write_png(const std::filesystem::path& path, const Image8& image) {
  write_file_atomic(path, encode_png(image));
}

}  // namespace sm
