#pragma once
/// PNG images of 8-bit grey, RGB or RGBA pixels, encoded by stb_image_write: deflate-compressed
/// scanlines, each with the PNG filter that suits it best (flat areas such as a checkerboard's
/// squares compress to almost nothing).
/// The bytes depend on the pixels only (stb's compression level and filter choice are left at their
/// defaults), so a texture is the same in every run and with any number of threads.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sm {

/// An 8-bit image, rows from the top, pixels left to right, channels interleaved.
struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 3;             ///< 1 (grey), 3 (RGB) or 4 (RGBA)
  std::vector<uint8_t> pixels;  ///< width × height × channels bytes
};

/// The PNG file of `image` (IHDR, IDAT, IEND). Throws InputError for a size outside
/// [1, 65535] × [1, 65535] or above 256 MiB of pixels, another channel count or a pixel buffer of
/// the wrong length.
std::string encode_png(const Image8& image);

/// encode_png written atomically to `path`.
void write_png(const std::filesystem::path& path, const Image8& image);

}  // namespace sm
