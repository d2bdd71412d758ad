#pragma once
/// SHA-256 (FIPS 180-4) of bytes and files, as lowercase hex: the hashes that a sequence job's
/// frame records hold (config, template, inputs, outputs), so that `sha256sum FILE` checks them.
/// Computed by OpenSSL's EVP interface, which picks the processor's SHA instructions (x86 SHA
/// extensions, ARMv8 crypto) or its own tuned assembly when there are none.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

struct evp_md_ctx_st;  // OpenSSL's EVP_MD_CTX, kept out of this header

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
  struct FreeContext {
    void operator()(evp_md_ctx_st* context) const;
  };
  std::unique_ptr<evp_md_ctx_st, FreeContext> context_;
  bool done_ = false;
};

/// SHA-256 of `bytes`, 64 lowercase hex digits.
std::string sha256_hex(std::string_view bytes);

/// SHA-256 of a file's content, read in blocks. Throws IoError naming the file.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace sm
