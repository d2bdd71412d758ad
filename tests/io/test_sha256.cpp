// SHA-256 against the FIPS 180-4 examples, in one piece and fed in odd chunks; files.
#include <catch2/catch.hpp>
#include <fstream>
#include <stdexcept>

#include "io/sha256.hpp"
#include "core/errors.hpp"
#include "support/temp_dir.hpp"

using namespace sm;

TEST_CASE("SHA-256 of the standard examples") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  const std::string million(1000000, 'a');
  CHECK(sha256_hex(million) == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // The same bytes in chunks of every size up to 130: block boundaries anywhere.
  for (size_t chunk = 1; chunk <= 130; chunk += 7) {
    Sha256 hash;
    for (size_t at = 0; at < 1000; at += chunk)
      hash.update(million.data() + at, std::min(chunk, 1000 - at));
    CHECK(hash.hex() == sha256_hex(million.substr(0, 1000)));
  }
  Sha256 done;
  CHECK(done.update("abc").hex() == sha256_hex("abc"));
  CHECK_THROWS_AS(done.update("d"), std::logic_error);  // one digest per object
  CHECK_THROWS_AS(done.hex(), std::logic_error);
}

TEST_CASE("SHA-256 of varied bytes around block boundaries (hashlib's digests)") {
  // Every byte value, not one repeated letter: whichever code OpenSSL picks for this processor
  // (SHA extensions, or its assembly without them: OPENSSL_ia32cap=":~0x20000000") must give
  // Python's hashlib.sha256 of these prefixes.
  std::string bytes(100003, '\0');
  for (size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<char>((i * 7919 + (i >> 8)) % 251);
  const std::pair<size_t, const char*> expected[] = {
      {55, "fd6f42647486d0fc7a569c6323bd5d0ffa383b9dac514f555877829297856d36"},
      {56, "72d3563b4bedfb81355271f6b89196e278891e5598aa35eda8c23d14d100510f"},
      {63, "34268e23e10f6a5c154eb09f7efe31b684c1e7a9d74ff4929e258f87178040a8"},
      {64, "690db028aa8003bab5c4afa5611cafa88040152b3b26a12a5e1ec3061939811b"},
      {65, "e88e7e570c255a8e47220ad916b6488134926b9e49b435ba51649f9d566fcc1d"},
      {127, "db0556ed6332f630b4cfea69e3bbe74cd79b4e7ca1cc4efbd02a018c10c16549"},
      {128, "989fefd3388c6e464233a5743bec7618edbb300a6957a39799ce64a640bada00"},
      {1000, "478eea67057d160a964e507852cd83be658fa6182c58014be889a9e10a991095"},
      {100003, "b843fbbea64f9664bc09ef0952198f6782808c2f422fb81bb1ff9cd37a00bdcd"}};
  for (const auto& [size, digest] : expected) {
    INFO(size << " bytes");
    CHECK(sha256_hex(std::string_view(bytes).substr(0, size)) == digest);
    Sha256 pieces;  // in uneven pieces: buffered blocks, then runs of whole blocks
    for (size_t at = 0; at < size; at += 1000 + at % 97)
      pieces.update(bytes.data() + at, std::min(size - at, 1000 + at % 97));
    CHECK(pieces.hex() == digest);
  }
}

TEST_CASE("SHA-256 of a file, and of a missing one") {
  test::TempDir dir;
  std::ofstream(dir / "abc.txt", std::ios::binary) << "abc";
  CHECK(sha256_file(dir / "abc.txt") ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK_THROWS_AS(sha256_file(dir / "none.txt"), IoError);
}
