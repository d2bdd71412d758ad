#include "io/png.hpp"

#include <stb_image_write.h>

#include <stdexcept>

#include "io/atomic_file.hpp"
#include "core/errors.hpp"

namespace sm {

namespace {

// stb_image_write hands the file over in pieces.
void append_png_bytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

std::string encode_png(const Image8& image) {
  if (image.width < 1 || image.width > 65535 || image.height < 1 || image.height > 65535)
    throw InputError("cannot write PNG: size " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + " is outside 1 to 65535 pixels per side");
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    throw InputError("cannot write PNG: " + std::to_string(image.channels) +
                     " channels (1, 3 or 4 are written)");
  const size_t row = size_t(image.width) * size_t(image.channels);
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height) +
                           "x" + std::to_string(image.channels);
  // stb_image_write sizes the filtered image and the growing compressed stream in int: 256 MiB
  // keeps both (and the doubling of the stream's buffer) below 2^31.
  if ((row + 1) * size_t(image.height) > size_t(1) << 28)
    throw InputError("cannot write PNG: " + size + " is more than 256 MiB of pixels");
  if (image.pixels.size() != row * size_t(image.height))
    throw InputError("cannot write PNG: " + std::to_string(image.pixels.size()) +
                     " bytes of pixels for " + size);
  std::string out;
  if (stbi_write_png_to_func(append_png_bytes, &out, image.width, image.height, image.channels,
                             image.pixels.data(), int(row)) == 0)
    throw std::runtime_error("stb_image_write could not encode a PNG of " + size);
  return out;
}

void write_png(const std::filesystem::path& path, const Image8& image) {
  write_file_atomic(path, encode_png(image));
}

}  // namespace sm
