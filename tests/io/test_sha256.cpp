// SHA-256 against the FIPS 180-4 examples, in one piece and fed in odd chunks; files.
#include <catch2/catch.hpp>
#include <fstream>

#include "io/sha256.hpp"
#include "mesh/errors.hpp"
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
}

TEST_CASE("SHA-256 of a file, and of a missing one") {
  test::TempDir dir;
  std::ofstream(dir / "abc.txt", std::ios::binary) << "abc";
  CHECK(sha256_file(dir / "abc.txt") ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK_THROWS_AS(sha256_file(dir / "none.txt"), IoError);
}
