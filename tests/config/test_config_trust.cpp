// The config side of the trust boundary: nesting capped at 64 levels with linear memory, NUL
// bytes in the text and in path strings refused, a FIFO or device given as the config refused
// without blocking.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>

#include "config/config.hpp"
#include "io/atomic_file.hpp"
#include "core/errors.hpp"
#include "support/error_of.hpp"
#include "support/temp_dir.hpp"

using namespace sm;
using test::error_of;
using json = nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string json_error(const std::string& text) {
  return error_of<ConfigError>([&] { parse_json_strict(text); });
}

std::string nested(int depth, const std::string& open, const std::string& close) {
  std::string text;
  for (int i = 0; i < depth; ++i) text += open;
  text += "1";
  for (int i = 0; i < depth; ++i) text += close;
  return text;
}

}  // namespace

TEST_CASE("config nesting is capped at 64 levels, naming the JSON path", "[config][trust]") {
  CHECK(parse_json_strict(nested(63, "[", "]")).is_array());
  CHECK(parse_json_strict(nested(64, "[", "]")).is_array());
  std::string path;
  for (int i = 0; i < 64; ++i) path += "[0]";
  CHECK(json_error(nested(65, "[", "]")) == path + ": nested deeper than 64 levels");
  CHECK(json_error("{\"input\": {\"a\": [1, " + nested(70, "{\"k\": ", "}") + "]}}")
            .find("input.a[1].k.k.k") == 0);
  // 200 KB of nesting (the quadratic path strings took 15 GB): refused at once.
  CHECK_THAT(json_error(nested(100000, "{\"key\": ", "}")),
             Catch::EndsWith(": nested deeper than 64 levels"));
  // Duplicate keys still name their path, built only for the message.
  CHECK(json_error(R"({"a": [0, {"b": {"c": 1, "c": 2}}]})") ==
        "a[1].b.c: duplicate key (each key may appear once)");
}

TEST_CASE("a NUL byte in config text or in a path string is a config error", "[config][trust]") {
  CHECK(json_error(std::string("{\"job\": \"sequence\"}\0{\"x\": 1}", 28)) ==
        "line 1, column 20: a NUL byte (JSON text cannot contain one; is this a binary file?)");
  CHECK(json_error(std::string("{\"a\":\n \"b\0c\"}", 13)) ==
        "line 2, column 4: a NUL byte (JSON text cannot contain one; is this a binary file?)");
  const std::string nul_path = R"({"job": "sequence", "input": {"frames": "f\u0000/../etc"},
                                   "output": {"dir": "o"}})";
  CHECK(error_of<ConfigError>([&] { parse_config(parse_json_strict(nul_path), "/base"); }) ==
        "input.frames: path contains a NUL character");
}

TEST_CASE("a config that is a FIFO or a device is refused without blocking", "[config][trust]") {
  const test::TempDir temp("config_fifo");
  const fs::path fifo = temp / "job.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // no writer: a blocking open would hang here
  CHECK(error_of<InputError>([&] { load_config(fifo); }) ==
        "'" + fifo.string() + "': not a regular file (a FIFO); only regular files are read");
  const fs::path zero = temp / "zero.json";
  fs::create_symlink("/dev/zero", zero);  // would be read without end
  CHECK(error_of<InputError>([&] { load_config(zero); }) ==
        "'" + zero.string() +
            "': not a regular file (a character device); only regular files are read");
}
