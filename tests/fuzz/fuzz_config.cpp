// Fuzz target: the config loader (config/config.hpp): strict JSON, then the mapping onto
// SequenceJobOptions.
#include <string>
#include <string_view>

#include "config/config.hpp"
#include "fuzz_targets.hpp"
#include "core/errors.hpp"

namespace sm::fuzz {

void fuzz_config(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  nlohmann::json document;
  try {
    document = parse_json_strict(text);
  } catch (const ConfigError&) {
    return;
  }
  // Whatever the strict parser accepts is JSON that nlohmann-json reads the same way.
  nlohmann::json plain;
  try {
    plain = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw FuzzFinding(std::string("strict JSON accepted what nlohmann-json refuses: ") + e.what());
  }
  expect(plain == document, "strict JSON and nlohmann-json parse the text differently");

  SequenceJobOptions config;
  try {
    config = parse_config(document, "/fuzz/configs");
  } catch (const ConfigError&) {
    return;
  }
  // The resolved config parses back to itself (documented for to_json).
  const nlohmann::json resolved = to_json(config);
  SequenceJobOptions again;
  try {
    again = parse_config(resolved, "/elsewhere");
  } catch (const ConfigError& e) {
    throw FuzzFinding(std::string("to_json of a parsed config does not parse: ") + e.what());
  }
  expect(to_json(again) == resolved, "to_json -> parse_config changes the config");
  (void)format_frame_range(config.input.range);
}

}  // namespace sm::fuzz
