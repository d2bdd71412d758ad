#pragma once
/// SHA-256 (FIPS 180-4) of bytes and files, as lowercase hex: the hashes that a sequence job's
/// frame records hold (config, template, inputs, outputs), so that `sha256sum FILE` checks them.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace sm {

/// Incremental SHA-256: update() any number of times, then hex() once.
class Sha256 {
 public:
  Sha256();
  Sha256& update(const void* data, size_t size);
  Sha256& update(std::string_view bytes) { return update(bytes.data(), bytes.size()); }
  /// The digest as 64 lowercase hex digits. Ends the computation (update() after it is an error).
  std::string hex();

 private:
  void block(const unsigned char* p);  // portable
  /// `count` 64-byte blocks: with the x86 SHA extensions when the processor has them.
  void blocks(const unsigned char* p, size_t count);
  std::array<uint32_t, 8> h_;
  std::array<unsigned char, 64> buffer_{};
  size_t buffered_ = 0;
  uint64_t length_ = 0;  // bytes hashed
  bool done_ = false;
};

/// SHA-256 of `bytes`, 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);

/// SHA-256 of a file's content, read in blocks. Throws IoError naming the file.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace sm
