// The configuration reference and the example configs against the options tables: the committed
// docs/configuration.md is what `seqmassage config --reference` prints, and the *_all_keys.json
// configs are what `seqmassage config --complete` writes of them (every key their job resolves);
// and the test files the docs point to exist.
#include <catch2/catch.hpp>

#include <filesystem>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "config/complete.hpp"
#include "config/config.hpp"
#include "config/reference.hpp"
#include "io/atomic_file.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace sm;

const fs::path kRoot = fs::path(SEQMASSAGE_TEST_DIR).parent_path();

json resolved(const json& doc) {
  const AnyJobOptions any = parse_any_config(doc, "/data/project/configs");
  return std::holds_alternative<SequenceJobOptions>(any)
             ? to_json(std::get<SequenceJobOptions>(any))
             : to_json(std::get<MeshJobOptions>(any));
}

}  // namespace

TEST_CASE("docs/configuration.md is the reference the options tables generate") {
  const auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
  };
  const std::vector<std::string> committed = lines(read_file(kRoot / "docs" / "configuration.md"));
  const std::vector<std::string> generated = lines(config_reference());
  INFO("regenerate it: seqmassage config --reference > docs/configuration.md");
  for (size_t i = 0; i < std::min(committed.size(), generated.size()); ++i) {
    INFO("docs/configuration.md:" << i + 1 << ":\n  committed: " << committed[i]
                                  << "\n  generated: " << generated[i]);
    REQUIRE(committed[i] == generated[i]);
  }
  CHECK(committed.size() == generated.size());
}

TEST_CASE("the reference lists every key of every job, by its JSON path") {
  const std::string reference = config_reference();
  // Every leaf of the resolved configs of a sequence job with every object present, and of a
  // crossparam job (which has every single-mesh key but input.reference).
  const json sequence = resolved(json::parse(R"({"job": "sequence",
      "input": {"synthetic": {}}, "output": {"dir": "o", "colored": true, "checker": true,
      "iterations": true}})"));
  const json gltf = resolved(json::parse(R"({"job": "sequence", "input": {"gltf": "a.glb"},
      "output": {"dir": "o", "format": "gltf"}})"));
  const json crossparam = resolved(json::parse(R"({"job": "crossparam",
      "input": {"mesh": "m.obj"}, "template": {"mesh": "t.obj"}, "output": {"dir": "o"}})"));
  int keys = 0;
  const std::function<void(const json&, const std::string&)> check = [&](const json& v,
                                                                         const std::string& path) {
    INFO(path);
    CHECK(reference.find("| `" + path + "` |") != std::string::npos);
    ++keys;
    if (v.is_object())
      for (const auto& item : v.items()) check(item.value(), path + "." + item.key());
  };
  for (const json* doc : {&sequence, &gltf, &crossparam})
    for (const auto& item : doc->items()) check(item.value(), item.key());
  CHECK(reference.find("| `input.reference` |") != std::string::npos);
  CHECK(keys > 100);
}

TEST_CASE("config --complete spells out every key, keeping what the file gives as written") {
  // Every leaf path of `resolved` (objects descended into; arrays and values are leaves).
  const std::function<void(const json&, const std::string&, std::vector<std::string>&)> leaves =
      [&](const json& v, const std::string& path, std::vector<std::string>& out) {
        if (!v.is_object() || v.empty()) {
          out.push_back(path);
          return;
        }
        for (const auto& item : v.items())
          leaves(item.value(), path.empty() ? item.key() : path + "." + item.key(), out);
      };
  const std::string given = R"({"job": "sequence", "output": {"dir": "out", "colored": true},
    "input": {"frames": "in"}, "massage": {"mu": 0.25}})";
  const nlohmann::ordered_json completed = complete_config(given, "/data/project");
  // The given keys first, in the file's order, and as written.
  std::vector<std::string> top;
  for (const auto& item : completed.items()) top.push_back(item.key());
  REQUIRE(top.size() > 4);
  CHECK(std::vector<std::string>(top.begin(), top.begin() + 4) ==
        std::vector<std::string>{"job", "output", "input", "massage"});
  CHECK(completed["input"]["frames"] == "in");
  CHECK(completed["output"]["colored"] == true);
  CHECK(completed["massage"].begin().key() == "mu");
  CHECK(completed["massage"]["mu"] == 0.25);
  // Every key the job resolves is there, at its default where the file left it out.
  const json resolved = to_json(parse_config(json::parse(given), "/data/project"));
  std::vector<std::string> paths;
  leaves(resolved, "", paths);
  CHECK(paths.size() > 40);
  const json as_json = completed;
  for (const std::string& path : paths) {
    INFO(path);
    if (path.rfind("output.colored", 0) == 0) continue;  // given as true
    const std::string pointer = "/" + std::regex_replace(path, std::regex("\\."), "/");
    CHECK(as_json.contains(json::json_pointer(pointer)));
  }
  CHECK(as_json["massage"]["iterations"] == resolved["massage"]["iterations"]);
  CHECK_THROWS_WITH(complete_config(R"({"job": "smooth", "input": {"mesh": 3}})", "/"),
                    "input.mesh: expected a path (a non-empty string), got 3");
}

TEST_CASE("configs/*_all_keys.json are what config --complete writes of them") {
  for (const std::string name :
       {"sequence_all_keys.json", "remesh_all_keys.json", "track_all_keys.json"}) {
    INFO("configs/" << name << "; regenerate it: seqmassage config --complete configs/" << name
                    << " > new.json && mv new.json configs/" << name);
    const fs::path file = kRoot / "configs" / name;
    CHECK(read_file(file) == complete_config_file(file));
  }
}

TEST_CASE("every test file the docs name exists") {
  // A test moved with its module (io/ -> config/) left the docs pointing at nothing.
  std::vector<fs::path> pages{kRoot / "README.md"};
  for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") pages.push_back(entry.path());
  // "pipeline/run/test_x.cpp" or "tests/pipeline/run/test_x.cpp": folders below tests/.
  const std::regex named(R"(\b(?:tests/)?((?:[a-z_]+/)+test_[a-z0-9_]+\.(cpp|py|sh))\b)");
  std::set<std::string> missing;
  int found = 0;
  for (const fs::path& page : pages) {
    const std::string text = read_file(page);
    for (auto m = std::sregex_iterator(text.begin(), text.end(), named);
         m != std::sregex_iterator(); ++m, ++found)
      if (!fs::exists(kRoot / "tests" / (*m)[1].str()))
        missing.insert(page.filename().string() + ": " + (*m)[1].str());
  }
  CHECK(found > 20);
  for (const std::string& m : missing) FAIL_CHECK(m << " does not exist under tests/");
}
