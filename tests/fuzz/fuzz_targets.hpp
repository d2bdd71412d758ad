#pragma once
/// Entry functions of the fuzz targets, one per reader: each parses arbitrary bytes, accepts the
/// reader's documented error (an sm::InputError or sm::ConfigError) and checks what the reader
/// promises of a successful parse. Anything else (a crash, a sanitizer report, another exception,
/// a FuzzFinding) is a finding. They are linked into the libFuzzer executables (tests/fuzz, clang
/// only) and into the test_fuzz_regressions suite, which replays the seed corpus and every kept
/// crash input with the normal compiler.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace sm::fuzz {

/// A broken promise of a reader (an invariant of its result), as opposed to a rejected input.
class FuzzFinding : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// Throws FuzzFinding(`what`) unless `ok`.
inline void expect(bool ok, const std::string& what) {
  if (!ok) throw FuzzFinding(what);
}

/// parse_obj; on success, checks the indices, that format_obj with the positions as read gives
/// back the same bytes, and that moved positions are written and read back exactly.
void fuzz_obj(const uint8_t* data, size_t size);

/// parse_off; on success, checks the mesh and that format_off reads back exactly.
void fuzz_off(const uint8_t* data, size_t size);

/// parse_ply with colours; on success, checks the mesh and colours, and that format_ply (ASCII
/// and binary) reads back exactly.
void fuzz_ply(const uint8_t* data, size_t size);

/// parse_json_strict then parse_config; a strictly parsed document must equal what nlohmann-json
/// parses, and a parsed config must survive to_json -> parse_config unchanged.
void fuzz_config(const uint8_t* data, size_t size);

/// load_gltf_sequence on the bytes written to a scratch file (GLB or glTF JSON), then the rest
/// mesh is checked and the first, middle and last frames are evaluated.
void fuzz_gltf(const uint8_t* data, size_t size);

/// parse_point_cache_header and decode_point_cache_frame on PC2 (first byte even) or MDD (odd)
/// bytes; on success, checks counts, sizes and coordinate limits, and that writing the cache back
/// with the same timing gives the same bytes.
void fuzz_point_cache(const uint8_t* data, size_t size);

}  // namespace sm::fuzz
