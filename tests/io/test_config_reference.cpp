// The configuration reference (docs/configuration.md) against the parser: every key it lists is a
// key the parser knows, every key the parser accepts is documented (or refused for that job with
// a message naming it), and every default the README writes as a JSON value is the one the parser
// resolves (to_json of a config that leaves the key out).
//
// The README marks its key tables with a line `<!-- config-keys: JOB ... -->` right before the
// table. The first cell of a row holds the key's full JSON path in backticks, optionally followed
// by "(JOB only)" or "(JOB, JOB only)". Columns whose header starts with "default" hold defaults:
// "default" for every job of the table, "default (JOB, JOB)" for the jobs named; a default cell
// that starts with a backticked JSON value is checked, any other text (e.g. "required") is not.
//
// The parser's own list of keys of each JSON object is read from its message for an unknown key
// that is near no known key ("unknown key (known keys: "a", "b" or "c")"), so the test follows
// the parser without a second list to keep in step.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "io/atomic_file.hpp"
#include "io/config.hpp"
#include "mesh/errors.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace sm;

const std::vector<std::string> kJobs = {"sequence", "remesh", "crossparam", "smooth"};
const std::string kProbe = "zzqqxxkkvvww";  // far from every key: the message lists them all

struct DocKey {
  std::string path;                               // e.g. "output.colored.max"
  std::set<std::string> jobs;                     // the jobs it is documented for
  std::map<std::string, std::string> default_of;  // job -> the default cell's text
  int line = 0;                                   // README line, for messages
};

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool code = false;
  for (size_t i = 1; i < line.size(); ++i) {  // skip the leading '|'
    const char c = line[i];
    if (c == '`') code = !code;
    if (c == '|' && !code) {
      const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
      cell.clear();
    } else {
      cell += c;
    }
  }
  return cells;
}

std::set<std::string> words_in(const std::string& text) {
  std::set<std::string> out;
  for (const std::string& job : kJobs)
    if (std::regex_search(text, std::regex("\\b" + job + "\\b"))) out.insert(job);
  return out;
}

// Every key row of every marked table of the README.
std::vector<DocKey> read_reference(const fs::path& readme) {
  std::istringstream in(read_file(readme));
  std::vector<DocKey> keys;
  std::string line;
  int number = 0;
  std::set<std::string> table_jobs;
  std::vector<std::string> header;
  enum { Outside, Header, Separator, Rows } state = Outside;
  const std::regex marker(R"(^<!-- config-keys: ([a-z ]+) -->\s*$)");
  while (std::getline(in, line)) {
    ++number;
    std::smatch m;
    if (std::regex_match(line, m, marker)) {
      table_jobs = words_in(m[1]);
      state = Header;
      continue;
    }
    if (state == Outside) continue;
    if (line.rfind("|", 0) != 0) {
      INFO("docs/configuration.md:" << number
                                    << ": a config-keys marker must be followed by its table");
      REQUIRE(state == Rows);
      state = Outside;
      continue;
    }
    if (state == Header) {
      header = split_row(line);
      state = Separator;
      continue;
    }
    if (state == Separator) {
      state = Rows;
      continue;
    }
    const std::vector<std::string> cells = split_row(line);
    INFO("docs/configuration.md:" << number << ": " << line);
    REQUIRE(cells.size() == header.size());
    std::smatch key;
    REQUIRE(std::regex_search(cells[0], key, std::regex(R"(^`([a-z_.]+)`(.*)$)")));
    DocKey k;
    k.path = key[1];
    k.line = number;
    k.jobs = table_jobs;
    std::smatch only;
    const std::string rest = key[2];
    if (std::regex_search(rest, only, std::regex(R"(\(([a-z, ]+) only\))"))) {
      k.jobs = words_in(only[1]);
      REQUIRE(!k.jobs.empty());
    }
    for (size_t c = 1; c < header.size(); ++c) {
      if (header[c].rfind("default", 0) != 0) continue;
      std::set<std::string> jobs = words_in(header[c]);
      if (jobs.empty()) jobs = table_jobs;
      for (const std::string& job : jobs)
        if (k.jobs.count(job)) k.default_of[job] = cells[c];
    }
    keys.push_back(std::move(k));
  }
  return keys;
}

// Minimal configs of each job that together reach every JSON object of its config: the first
// leaves every optional output off; the others switch on what has keys of its own.
std::vector<json> bases(const std::string& job) {
  if (job == "sequence")
    return {
        json::parse(R"({"job": "sequence", "input": {"frames": "take"}, "output": {"dir": "o"}})"),
        json::parse(R"({"job": "sequence", "input": {"synthetic": {}},
            "output": {"dir": "o", "colored": true, "checker": true, "iterations": true}})"),
        json::parse(R"({"job": "sequence", "input": {"gltf": "a.glb"},
            "output": {"dir": "o", "format": "gltf"}})"),
        json::parse(R"({"job": "sequence", "input": {"frames": "take"},
            "template": {"mesh": "rest.obj"}, "output": {"dir": "o"}})"),
    };
  if (job == "remesh")
    return {json::parse(R"({"job": "remesh", "input": {"mesh": "m.off", "reference": "n.off"},
        "output": {"dir": "o"}})")};
  if (job == "crossparam")
    return {json::parse(R"({"job": "crossparam", "input": {"mesh": "m.obj"},
        "template": {"mesh": "t.obj"}, "output": {"dir": "o"}})")};
  return {json::parse(R"({"job": "smooth", "input": {"mesh": "m.obj"}, "output": {"dir": "o"}})")};
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream s(path);
  for (std::string part; std::getline(s, part, '.');) parts.push_back(part);
  return parts;
}

std::string join(const std::vector<std::string>& parts, size_t n) {
  std::string out;
  for (size_t i = 0; i < n; ++i) out += (i ? "." : "") + parts[i];
  return out;
}

// The value at `path` in `doc`, or nullptr.
const json* find(const json& doc, const std::string& path) {
  const json* v = &doc;
  for (const std::string& part : split_path(path)) {
    if (!v->is_object() || !v->contains(part)) return nullptr;
    v = &(*v)[part];
  }
  return v;
}

// `doc` with `value` at `path`; objects are created (or replace a non-object) on the way.
json with(json doc, const std::string& path, const json& value) {
  json* v = &doc;
  const std::vector<std::string> parts = split_path(path);
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    json& next = (*v)[parts[i]];
    if (!next.is_object()) next = json::object();
    v = &next;
  }
  (*v)[parts.back()] = value;
  return doc;
}

std::optional<std::string> config_error(const json& doc) {
  try {
    parse_any_config(doc, "/data/project/configs");
  } catch (const ConfigError& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

json resolved(const json& doc) {
  const AnyJobConfig any = parse_any_config(doc, "/data/project/configs");
  return std::holds_alternative<JobConfig>(any) ? to_json(std::get<JobConfig>(any))
                                                : to_json(std::get<MeshJobConfig>(any));
}

// The keys the parser knows in the object at `path` ("" = the top level), from its message for
// an unknown key; nullopt if no base config reaches that object.
std::optional<std::set<std::string>> known_keys(const std::string& job, const std::string& path) {
  const std::string probe = path.empty() ? kProbe : path + "." + kProbe;
  for (const json& base : bases(job)) {
    const auto error = config_error(with(base, probe, 0));
    const std::string lead = probe + ": unknown key (known keys: ";
    if (!error || error->rfind(lead, 0) != 0) continue;
    std::set<std::string> keys;
    const std::string list = error->substr(lead.size());
    const std::regex quoted("\"([^\"]+)\"");
    for (auto it = std::sregex_iterator(list.begin(), list.end(), quoted);
         it != std::sregex_iterator(); ++it)
      keys.insert((*it)[1]);
    return keys;
  }
  return std::nullopt;
}

// A refusal of a key the parser knows but the job does not take (e.g. "input.reference" in a
// smooth job), as opposed to a wrong value.
bool is_refusal(const std::string& message) {
  for (const char* phrase : {"only for", "only applies", "not used by", "not available"})
    if (message.find(phrase) != std::string::npos) return true;
  return false;
}

fs::path readme_path() {
  return fs::path(SEQMASSAGE_TEST_DIR).parent_path() / "docs" / "configuration.md";
}

}  // namespace

TEST_CASE("the README documents exactly the keys the parser accepts, for every job") {
  const std::vector<DocKey> doc = read_reference(readme_path());
  REQUIRE(doc.size() > 50);
  for (const std::string& job : kJobs) {
    std::vector<json> resolved_bases;
    for (const json& base : bases(job)) resolved_bases.push_back(resolved(base));

    // Every documented key is accepted: some base config resolves it (to_json writes every key
    // in effect), and giving it that value explicitly is accepted.
    std::map<std::string, std::set<std::string>> children;  // object path ("" = top) -> keys
    for (const DocKey& k : doc) {
      if (!k.jobs.count(job)) continue;
      INFO("docs/configuration.md:" << k.line << ": " << k.path << " (job " << job << ")");
      bool accepted = false;
      for (size_t b = 0; b < resolved_bases.size() && !accepted; ++b)
        if (const json* value = find(resolved_bases[b], k.path)) {
          const auto error = config_error(with(bases(job)[b], k.path, *value));
          INFO("given its resolved value " << value->dump() << ": " << error.value_or("accepted"));
          CHECK_FALSE(error);
          accepted = true;
        }
      CHECK(accepted);  // documented, but no config of this job takes it
      const std::vector<std::string> parts = split_path(k.path);
      for (size_t n = 0; n < parts.size(); ++n) children[join(parts, n)].insert(parts[n]);
    }
    REQUIRE(children.count(""));

    // Every key the parser knows in these objects is documented, or refused for this job.
    for (const auto& [object, documented] : children) {
      INFO("job " << job << ", object \"" << object << "\"");
      const auto known = known_keys(job, object);
      REQUIRE(known);  // a documented object the parser does not have
      for (const std::string& key : documented) {
        INFO("documented key " << key);
        CHECK(known->count(key));
      }
      for (const std::string& key : *known) {
        if (documented.count(key)) continue;
        const std::string path = object.empty() ? key : object + "." + key;
        INFO("undocumented key " << path << " must be refused for job " << job);
        for (size_t b = 0; b < resolved_bases.size(); ++b) {
          CHECK_FALSE(find(resolved_bases[b], path));
          const auto error = config_error(with(bases(job)[b], path, 0));
          REQUIRE(error);
          INFO(*error);
          CHECK(error->rfind(path + ": ", 0) == 0);
          CHECK(is_refusal(*error));
        }
      }
    }
  }
}

TEST_CASE("the README's defaults are the parser's") {
  const std::vector<DocKey> doc = read_reference(readme_path());
  int checked = 0;
  for (const DocKey& k : doc)
    for (const auto& [job, cell] : k.default_of) {
      if (cell.empty() || cell[0] != '`') continue;  // text: "required", "the keyframe times"
      INFO("docs/configuration.md:" << k.line << ": " << k.path << " (job " << job << "), default "
                                    << cell);
      const std::string literal = cell.substr(1, cell.find('`', 1) - 1);
      json expected;
      REQUIRE_NOTHROW(expected = json::parse(literal));
      bool found = false;
      for (const json& base : bases(job)) {
        const json config = resolved(base);
        if (const json* actual = find(config, k.path)) {
          CHECK(*actual == expected);
          // ... and the documented default is a value the parser accepts.
          CHECK_FALSE(config_error(with(base, k.path, expected)));
          found = true;
          break;
        }
      }
      CHECK(found);  // no base config resolves this key: add one to bases()
      ++checked;
    }
  CHECK(checked > 60);
}

TEST_CASE("configs/*_all_keys.json spell out every key their job resolves") {
  const fs::path configs = fs::path(SEQMASSAGE_TEST_DIR).parent_path() / "configs";
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
  int files = 0;
  for (const std::string name : {"sequence_all_keys.json", "remesh_all_keys.json"}) {
    INFO("configs/" << name);
    const json written = parse_json_strict(read_file(configs / name));
    std::vector<std::string> paths;
    leaves(resolved(written), "", paths);
    CHECK(paths.size() > 20);
    for (const std::string& path : paths) {
      INFO(path);
      CHECK(find(written, path));
    }
    ++files;
  }
  CHECK(files == 2);
}
