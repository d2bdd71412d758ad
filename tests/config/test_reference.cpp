// The configuration reference and the example configs against the options tables: the committed
// docs/configuration.md is what `seqmassage config --reference` prints, and the *_all_keys.json
// configs spell out every key their job resolves; and the test files the docs point to exist.
#include <catch2/catch.hpp>

#include <filesystem>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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

TEST_CASE("configs/*_all_keys.json spell out every key their job resolves") {
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
  const auto find = [](const json& doc, const std::string& path) {
    const json* v = &doc;
    for (size_t begin = 0; v && begin <= path.size();) {
      const size_t dot = std::min(path.find('.', begin), path.size());
      const std::string part = path.substr(begin, dot - begin);
      v = v->is_object() && v->contains(part) ? &(*v)[part] : nullptr;
      begin = dot + 1;
    }
    return v != nullptr;
  };
  for (const std::string name : {"sequence_all_keys.json", "remesh_all_keys.json"}) {
    INFO("configs/" << name);
    const json written = parse_json_strict(read_file(kRoot / "configs" / name));
    std::vector<std::string> paths;
    leaves(resolved(written), "", paths);
    CHECK(paths.size() > 20);
    for (const std::string& path : paths) {
      INFO(path);
      CHECK(find(written, path));
    }
  }
}

TEST_CASE("every test file the docs name exists") {
  // A test moved with its module (io/ -> config/) left the docs pointing at nothing.
  std::vector<fs::path> pages{kRoot / "README.md"};
  for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
    if (entry.path().extension() == ".md") pages.push_back(entry.path());
  const std::regex named(R"(\b([a-z]+/test_[a-z0-9_]+\.(cpp|py|sh))\b)");
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
