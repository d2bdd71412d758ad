#pragma once
/// PNG images written without a compression library: 8-bit grey, RGB or RGBA, every scanline
/// with filter 0 (none), the zlib stream made of stored (uncompressed) deflate blocks, checked by
/// CRC-32 (chunks) and Adler-32 (zlib). Any PNG decoder reads them; they are about as large as
/// the raw pixels (a 256×256 RGB texture is 197 KB), which is fine for test textures.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sm {

/// An 8-bit image, rows from the top, pixels left to right, channels interleaved.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 3;             ///< 1 (grey), 3 (RGB) or 4 (RGBA)
  std::vector<uint8_t> pixels;  ///< width × height × channels bytes
};

/// CRC-32 (ISO 3309, polynomial 0xEDB88320, as PNG chunks use), continued from `crc` (start 0).
uint32_t crc32(std::string_view bytes, uint32_t crc = 0);

/// Adler-32 (RFC 1950) of `bytes`.
uint32_t adler32(std::string_view bytes);

/// `data` as a zlib stream (RFC 1950) of stored deflate blocks (RFC 1951, BTYPE 00, at most
/// 65535 bytes each; one empty final block for empty data).
std::string zlib_stored(std::string_view data);

/// The PNG file of `image` (IHDR, one IDAT, IEND). Byte-deterministic. Throws InputError for a
/// size outside [1, 65535] × [1, 65535], another channel count or a pixel buffer of the wrong
/// length.
std::string encode_png(const Image8& image);

/// encode_png written atomically to `path`.
void write_png(const std::filesystem::path& path, const Image8& image);

}  // namespace sm
