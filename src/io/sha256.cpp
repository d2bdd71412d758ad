#include "io/sha256.hpp"

#include <openssl/evp.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "io/input_file.hpp"
#include "core/errors.hpp"

namespace sm {

namespace {

// The SHA-256 implementation of OpenSSL's default provider, fetched once: EVP_sha256() would
// look it up again at every EVP_DigestInit_ex, and the records hash many short strings.
const EVP_MD* sha256_method() {
  static const EVP_MD* method = EVP_MD_fetch(nullptr, "SHA256", nullptr);
  if (!method) throw std::runtime_error("OpenSSL has no SHA-256 (EVP_MD_fetch failed)");
  return method;
}

}  // namespace

void Sha256::FreeContext::operator()(evp_md_ctx_st* context) const {
  EVP_MD_CTX_free(context);
}

Sha256::Sha256() : context_(EVP_MD_CTX_new()) {
  if (!context_ || EVP_DigestInit_ex(context_.get(), sha256_method(), nullptr) != 1)
    throw std::runtime_error("OpenSSL: cannot start a SHA-256 digest");
}

Sha256& Sha256::update(const void* data, size_t size) {
  if (done_) throw std::logic_error("Sha256::update after hex()");
  if (size > 0 && EVP_DigestUpdate(context_.get(), data, size) != 1)
    throw std::runtime_error("OpenSSL: SHA-256 update failed");
  return *this;
}

std::string Sha256::hex() {
  if (done_) throw std::logic_error("Sha256::hex called twice");
  done_ = true;
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(context_.get(), digest, &size) != 1 || size != 32)
    throw std::runtime_error("OpenSSL: SHA-256 final failed");
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < size; ++i) {
    out += digits[digest[i] >> 4];
    out += digits[digest[i] & 0xf];
  }
  return out;
}

std::string sha256_hex(std::string_view bytes) {
  return Sha256().update(bytes).hex();
}

std::string sha256_file(const std::filesystem::path& path) {
  InputFile in(path);  // a FIFO or a device named as an input is refused, not read forever
  Sha256 hash;
  std::vector<char> buffer(1 << 20);
  while (const size_t n = in.read(buffer.data(), buffer.size())) hash.update(buffer.data(), n);
  return hash.hex();
}

}  // namespace sm
