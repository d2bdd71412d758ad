// The sequence job's visual output keys: output.colored, output.checker, output.iterations
// (true, false or an object), frame selections, defaults, round trip and messages by JSON path.
#include <catch2/catch.hpp>

#include "config/config.hpp"
#include "core/errors.hpp"

using namespace sm;
using json = nlohmann::json;

namespace {

SequenceJobOptions parse_output(const std::string& output) {
  const std::string text =
      R"({"job": "sequence", "input": {"frames": "take1"}, "output": )" + output + "}";
  return parse_config(parse_json_strict(text), "/data/project/configs");
}

std::string error_of(const std::string& output) {
  try {
    parse_output(output);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("visual outputs are off by default and take their defaults with true") {
  const SequenceJobOptions off = parse_output(R"({"dir": "o"})");
  CHECK_FALSE(off.output.colored.enabled);
  CHECK_FALSE(off.output.checker.enabled);
  CHECK_FALSE(off.output.iterations.enabled);
  const json resolved_off = to_json(off)["output"];
  CHECK(resolved_off["colored"] == false);
  CHECK(resolved_off["checker"] == false);
  CHECK(resolved_off["iterations"] == false);

  const SequenceJobOptions on =
      parse_output(R"({"dir": "o", "colored": true, "checker": true, "iterations": true})");
  const OutputOptions& o = on.output;
  CHECK(o.colored.enabled);
  CHECK(o.colored.frames.kind == FrameSelection::Kind::All);
  CHECK(o.colored.max == 0.1);
  CHECK(o.colored.colors == ShearColorMode::Faces);
  CHECK(o.checker.enabled);
  CHECK(o.checker.uv == CheckerUvSource::Auto);
  CHECK(o.checker.cells == 8);
  CHECK(o.checker.cell_size == 4.0);
  CHECK(o.iterations.enabled);
  CHECK(o.iterations.frames.contains(12345));
  CHECK_FALSE(o.iterations.shear_frames.contains(0));
  const json r = to_json(on)["output"];
  CHECK(r["colored"] == json::parse(R"({"frames": "all", "max": 0.1, "colors": "faces"})"));
  CHECK(r["checker"] ==
        json::parse(R"({"frames": "all", "uv": "auto", "cells": 8, "cell_size": 4.0})"));
  CHECK(r["iterations"] == json::parse(R"({"frames": "all", "shear_frames": []})"));
  CHECK_FALSE(parse_output(R"({"dir": "o", "colored": false})").output.colored.enabled);
}

TEST_CASE("visual output objects: every key, frame selections, round trip") {
  const SequenceJobOptions c = parse_output(R"({"dir": "o",
      "colored": {"frames": [7, 3, 7, 0], "max": 0.25, "colors": "vertices"},
      "checker": {"frames": "2:10:4", "uv": "charts", "cells": 16, "cell_size": 2.5},
      "iterations": {"frames": "5:", "shear_frames": [9]}})");
  const OutputOptions& o = c.output;
  CHECK(o.colored.enabled);
  CHECK(o.colored.frames.list == std::vector<int>{0, 3, 7});  // sorted, without repeats
  CHECK(o.colored.frames.contains(3));
  CHECK_FALSE(o.colored.frames.contains(4));
  CHECK(o.colored.max == 0.25);
  CHECK(o.colored.colors == ShearColorMode::Vertices);
  CHECK(o.checker.frames.kind == FrameSelection::Kind::Range);
  for (int i = 0; i < 14; ++i) CHECK(o.checker.frames.contains(i) == (i == 2 || i == 6));
  CHECK(o.checker.uv == CheckerUvSource::Charts);
  CHECK(o.checker.cells == 16);
  CHECK(o.checker.cell_size == 2.5);
  CHECK_FALSE(o.iterations.frames.contains(4));
  CHECK(o.iterations.frames.contains(5000));
  CHECK(o.iterations.shear_frames.list == std::vector<int>{9});
  // A single index as a range string selects that frame.
  CHECK(parse_output(R"({"dir": "o", "colored": {"frames": "4:5"}})")
            .output.colored.frames.contains(4));

  const json resolved = to_json(c);
  CHECK(resolved["output"]["colored"]["frames"] == json::parse("[0, 3, 7]"));
  CHECK(resolved["output"]["checker"]["frames"] == "2:10:4");
  CHECK(resolved["output"]["iterations"]["frames"] == "5::1");
  CHECK(to_json(parse_config(resolved, "/elsewhere")) == resolved);
}

TEST_CASE("visual output keys are checked, messages name the JSON path") {
  CHECK(error_of(R"({"dir": "o", "colored": "yes"})") ==
        "output.colored: expected true, false or an object with the keys \"frames\", \"max\", or "
        "\"colors\", got \"yes\"");
  CHECK(error_of(R"({"dir": "o", "colored": {"max": 0}})") ==
        "output.colored.max: expected a number in (0, 1e+06], got 0");
  CHECK(error_of(R"({"dir": "o", "colored": {"colours": "faces"}})") ==
        "output.colored.colours: unknown key (did you mean \"colors\"?)");
  CHECK(error_of(R"({"dir": "o", "colored": {"colors": "face"}})") ==
        "output.colored.colors: expected \"faces\" or \"vertices\", got \"face\" (did you mean "
        "\"faces\"?)");
  CHECK(error_of(R"({"dir": "o", "colored": {"frames": [1, -2]}})") ==
        "output.colored.frames[1]: expected an integer >= 0, got -2");
  CHECK(error_of(R"({"dir": "o", "colored": {"frames": "some"}})") ==
        "output.colored.frames: expected \"all\", an array of frame indices or a range "
        "\"A:B[:STEP]\", got \"some\"");
  CHECK(error_of(R"({"dir": "o", "checker": {"frames": "5:2"}})") ==
        "output.checker.frames: B must be >= A, got \"5:2\"");
  CHECK(error_of(R"({"dir": "o", "checker": {"frames": {"start": 1}}})") ==
        "output.checker.frames: expected \"all\", an array of frame indices or a range "
        "\"A:B[:STEP]\", got an object");
  CHECK(error_of(R"({"dir": "o", "checker": {"cells": 0}})") ==
        "output.checker.cells: expected an integer in [1, 64], got 0");
  CHECK(error_of(R"({"dir": "o", "checker": {"uv": "planar"}})")
            .rfind("output.checker.uv: expected \"auto\" or \"charts\", got \"planar\"", 0) == 0);
  CHECK(error_of(R"({"dir": "o", "checker": {"cell_size": -1}})") ==
        "output.checker.cell_size: expected a number in (0, 1e+06], got -1");
  CHECK(error_of(R"({"dir": "o", "iterations": {"shear_frame": [1]}})") ==
        "output.iterations.shear_frame: unknown key (did you mean \"shear_frames\"?)");
  CHECK(error_of(R"({"dir": "o", "iterations": 1})") ==
        "output.iterations: expected true, false or an object with the keys \"frames\" or "
        "\"shear_frames\", got 1");
  CHECK(error_of(R"({"dir": "o", "colord": true})") ==
        "output.colord: unknown key (did you mean \"colored\"?)");
}
