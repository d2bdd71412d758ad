#include "config/complete.hpp"

#include <algorithm>

#include "config/config.hpp"
#include "io/atomic_file.hpp"

namespace sm {
namespace fs = std::filesystem;
using json = nlohmann::json;
using ordered = nlohmann::ordered_json;

namespace {

// `given` with the keys only `resolved` has appended, object by object. A value both have is
// given's (a relative path stays as written; a toggle given as true stays true).
ordered with_defaults(ordered given, const json& resolved) {
  if (!given.is_object() || !resolved.is_object()) return given;
  for (const auto& item : resolved.items()) {
    const auto it = given.find(item.key());
    if (it == given.end())
      given[item.key()] = ordered(item.value());
    else
      *it = with_defaults(std::move(*it), item.value());
  }
  return given;
}

// JSON indented by 2, as dump(2) but with an array of numbers or strings on one line, so that
// a config stays readable ("shear_bins": [0, 0.01, ...], "frames": [0, 14]).
void format(const ordered& v, const std::string& indent, std::string& out) {
  const auto structured = [](const ordered& e) { return e.is_structured(); };
  if (v.is_array() && std::none_of(v.begin(), v.end(), structured)) {
    out += "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i > 0 ? ", " : "") + v[i].dump();
    out += "]";
    return;
  }
  if (!v.is_structured() || v.empty()) {
    out += v.dump();
    return;
  }
  const std::string inner = indent + "  ";
  out += v.is_object() ? "{\n" : "[\n";
  size_t i = 0;
  for (auto it = v.begin(); it != v.end(); ++it, ++i) {
    out += inner;
    if (v.is_object()) out += ordered(it.key()).dump() + ": ";
    format(*it, inner, out);
    out += i + 1 < v.size() ? ",\n" : "\n";
  }
  out += indent + (v.is_object() ? "}" : "]");
}

}  // namespace

ordered complete_config(const std::string& text, const fs::path& base_dir) {
  const AnyJobOptions any = parse_any_config(parse_json_strict(text), base_dir);
  const json resolved = std::visit([](const auto& options) { return to_json(options); }, any);
  // The file's own order (parse_json_strict has already refused what JSON does not allow).
  return with_defaults(ordered::parse(text), resolved);
}

std::string complete_config_file(const fs::path& path) {
  std::string out;
  format(complete_config(read_file(path), fs::absolute(path).parent_path()), "", out);
  return out + "\n";
}

}  // namespace sm
