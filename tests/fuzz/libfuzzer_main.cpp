// libFuzzer entry point of one target, chosen at compile time by SEQMASSAGE_FUZZ_TARGET (e.g.
// fuzz_obj). A FuzzFinding or any exception the target does not expect is reported and aborts,
// which libFuzzer records as a crash with the input that caused it.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "fuzz_targets.hpp"

#ifndef SEQMASSAGE_FUZZ_TARGET
#error "define SEQMASSAGE_FUZZ_TARGET to one of the functions of fuzz_targets.hpp"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    sm::fuzz::SEQMASSAGE_FUZZ_TARGET(data, size);
  } catch (const sm::fuzz::FuzzFinding& e) {
    std::fprintf(stderr, "FUZZ FINDING: %s\n", e.what());
    std::abort();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FUZZ FINDING: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
