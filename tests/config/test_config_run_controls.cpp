// The sequence job's keys for unattended runs: "checks" (when a frame fails), "output.on_failure",
// "shard" and "resume"; --shard's I/N.
#include <catch2/catch.hpp>

#include "config/config.hpp"
#include "core/errors.hpp"

using namespace sm;
using json = nlohmann::json;

namespace {

const std::string kMinimal =
    R"({"job": "sequence", "input": {"frames": "take1"}, "output": {"dir": "out"}})";

SequenceJobOptions parse_with(const std::string& key, const std::string& value) {
  json j = json::parse(kMinimal);
  if (key.rfind("output.", 0) == 0)
    j["output"][key.substr(7)] = json::parse(value);
  else
    j[key] = json::parse(value);
  return parse_config(j, "/base");
}

std::string error_with(const std::string& key, const std::string& value) {
  try {
    parse_with(key, value);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE(
    "run controls default to: fail beyond 0.5% folded, copy the input, one shard, no resume") {
  const SequenceJobOptions c = parse_config(json::parse(kMinimal), "/base");
  CHECK_FALSE(c.checks.max_folded_triangles);
  REQUIRE(c.checks.max_folded_fraction);
  CHECK(*c.checks.max_folded_fraction == 0.005);
  CHECK(c.output.on_failure == OnFailure::CopyInput);
  CHECK(c.shard.index == 0);
  CHECK(c.shard.count == 1);
  CHECK_FALSE(c.shard.sharded());
  CHECK_FALSE(c.resume);
  const json j = to_json(c);
  CHECK(j["checks"] ==
        json::parse(R"({"max_folded_triangles": null, "max_folded_fraction": 0.005,
                         "repair_folds": true, "repair_rings": 2, "repair_rounds": 4})"));
  CHECK(j["output"]["on_failure"] == "copy_input");
  CHECK(j["shard"] == json::parse(R"({"index": 0, "count": 1})"));
  CHECK(j["resume"] == false);
}

TEST_CASE("run controls are set by their keys and round-trip through to_json") {
  json j = json::parse(kMinimal);
  j["checks"] = {{"max_folded_triangles", 3}, {"max_folded_fraction", nullptr}};
  j["output"]["on_failure"] = "skip";
  j["shard"] = {{"index", 2}, {"count", 5}};
  j["resume"] = true;
  const SequenceJobOptions c = parse_config(j, "/base");
  CHECK(c.checks.max_folded_triangles == 3);
  CHECK_FALSE(c.checks.max_folded_fraction);
  CHECK(c.output.on_failure == OnFailure::Skip);
  CHECK(c.shard.index == 2);
  CHECK(c.shard.count == 5);
  CHECK(c.resume);
  const json resolved = to_json(c);
  CHECK(to_json(parse_config(resolved, "/elsewhere")) == resolved);
}

TEST_CASE("run controls: wrong values name the key") {
  CHECK(error_with("checks", R"({"max_folded_triangles": -1})") ==
        "checks.max_folded_triangles: expected an integer >= 0, got -1");
  CHECK(error_with("checks", R"({"max_folded_fraction": 2})") ==
        "checks.max_folded_fraction: expected a number in [0, 1], got 2");
  CHECK(error_with("checks", R"({"max_folded_triangle": 2})") ==
        "checks.max_folded_triangle: unknown key (did you mean \"max_folded_triangles\"?)");
  CHECK(error_with("output.on_failure", R"("copy")") ==
        "output.on_failure: expected \"copy_input\" or \"skip\", got \"copy\"");
  CHECK(error_with("shard", R"({"index": 3, "count": 3})") ==
        "shard.index: expected an integer in [0, 2], got 3");
  CHECK(error_with("shard", R"({"count": 0})") ==
        "shard.count: expected an integer in [1, 100000], got 0");
  CHECK(error_with("resume", R"("yes")") == "resume: expected true or false, got \"yes\"");
}

TEST_CASE("--shard I/N is 0-based") {
  const ShardOptions s = parse_shard("2/3", "--shard");
  CHECK(s.index == 2);
  CHECK(s.count == 3);
  CHECK(format_shard(s) == "2/3");
  const auto message = [](const std::string& text) {
    try {
      parse_shard(text, "--shard");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message("3/3") ==
        "--shard: I is 0-based and must be below N (like a Slurm array task id or a Kubernetes "
        "JOB_COMPLETION_INDEX), got \"3/3\"");
  CHECK(message("1") == "--shard: expected I/N: shard I (0-based) of N, e.g. 0/4, got \"1\"");
  CHECK(message("a/2") == "--shard: expected I/N: shard I (0-based) of N, e.g. 0/4, got \"a/2\"");
  CHECK(message("0/0") == "--shard: N must be in [1, 100000], got \"0/0\"");
}
