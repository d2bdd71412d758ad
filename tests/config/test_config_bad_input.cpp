// The bad-input catalogue for config files: empty, truncated and invalid JSON
// with its line and column, JSON that is valid but not a config, values of the wrong type at every
// level with their JSON path, and files that cannot be read.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "config/config.hpp"
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

std::string config_error(const std::string& text) {
  return error_of<ConfigError>([&] { parse_config(json::parse(text), "/base"); });
}

const std::string kRest = R"("input": {"frames": "f"}, "output": {"dir": "o"})";

}  // namespace

TEST_CASE("empty, truncated and invalid JSON names the line and column", "[config][errors]") {
  CHECK(json_error("") ==
        "line 1, column 1: syntax error while parsing value - unexpected end of input; expected "
        "'[', '{', or a literal");
  CHECK(json_error("  \n  ").rfind("line 2, column 2: syntax error", 0) == 0);
  CHECK(json_error("{\"job\": \"seq") ==
        "line 1, column 12: syntax error while parsing value - invalid string: missing closing "
        "quote; last read: '\"seq'");
  CHECK(json_error("{\"job\": \"sequence\",\n \"input\": {") ==
        "line 2, column 11: syntax error while parsing object key - unexpected end of input; "
        "expected string literal");
  CHECK(json_error("{'job': 1}").rfind("line 1, column 2: syntax error", 0) == 0);
  CHECK(json_error("{\"mu\": NaN}").rfind("line 1, column 8: syntax error", 0) == 0);
  CHECK(json_error("{\"a\": \"\xff\"}").find("ill-formed UTF-8 byte") != std::string::npos);
  CHECK(json_error("{\"threads\": 1e999}") == "line 1, column 17: number overflow parsing '1e999'");
}

TEST_CASE("valid JSON that is not a config names the JSON path", "[config][errors]") {
  CHECK(config_error("[1, 2]") == "config: expected an object, got an array");
  CHECK(config_error("\"sequence\"") == "config: expected an object, got \"sequence\"");
  CHECK(config_error("{\"job\": null, " + kRest + "}") == "job: expected \"sequence\", got null");
  CHECK(config_error(R"({"job": "sequence", "input": "f", "output": {"dir": "o"}})") ==
        "input: expected an object, got \"f\"");
  CHECK(config_error(R"({"job": "sequence", "input": {"frames": "f"}, "output": {"dir": ""}})") ==
        "output.dir: expected a path (a non-empty string), got \"\"");
  CHECK(config_error(R"({"job": "sequence", "input": {"frames": 3}, "output": {"dir": "o"}})") ==
        "input.frames: expected a path (a non-empty string), got 3");
  const std::string base = R"({"job": "sequence", )" + kRest;
  CHECK(config_error(base + R"(, "threads": 1e20})") ==
        "threads: expected an integer in [0, 4096], got 1e+20");
  CHECK(config_error(base + R"(, "threads": -1})") ==
        "threads: expected an integer in [0, 4096], got -1");
  CHECK(config_error(base + R"(, "threads": true})") ==
        "threads: expected an integer in [0, 4096], got true");
  CHECK(config_error(base + R"(, "template": {"frame": 18446744073709551615}})") ==
        "template.frame: expected an integer >= 0, got 18446744073709551615");
  CHECK(config_error(base + R"(, "massage": []})") == "massage: expected an object, got an array");
  CHECK(config_error(base + R"(, "massage": {"pinned": [1, "a"]}})") ==
        "massage.pinned[1]: expected an integer >= 0, got \"a\"");
  CHECK(config_error(base + R"(, "massage": {"mu": null}})") ==
        "massage.mu: expected \"auto\" or a number in [0, 1), got null");
  CHECK(config_error(
            R"({"job": "sequence", "input": {"frames": "f", "range": {"start": 5, "stop": 2}},)"
            R"( "output": {"dir": "o"}})") == "input.range.stop: expected an integer >= 5, got 2");
}

TEST_CASE("a config file that cannot be read is an I/O error naming it", "[config][errors]") {
  const test::TempDir temp("config_bad");
  const fs::path& dir = temp.path();
  fs::create_directories(dir / "folder.json");
  const std::string missing = error_of<IoError>([&] { load_config(dir / "missing.json"); });
  CHECK(missing ==
        "cannot open '" + (dir / "missing.json").string() + "': No such file or directory");
  const std::string folder = error_of<IoError>([&] { load_config(dir / "folder.json"); });
  CHECK(folder == "cannot read '" + (dir / "folder.json").string() + "': Is a directory");
  std::ofstream(dir / "empty.json");
  CHECK(error_of<ConfigError>([&] {
          load_config(dir / "empty.json");
        }).rfind("line 1, column 1: syntax error", 0) == 0);
}
