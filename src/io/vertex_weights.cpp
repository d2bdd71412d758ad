#include "io/vertex_weights.hpp"

#include <algorithm>
#include <cmath>

#include "io/atomic_file.hpp"
#include "io/ply.hpp"
#include "io/text_scan.hpp"
#include "core/errors.hpp"

namespace sm {
namespace {

std::string number_text(double value) {
  std::string text;
  append_double(text, value);
  return text;
}

// "weights.ply#quality" -> ("weights.ply", "quality"); anything else -> (spec, "").
std::pair<std::filesystem::path, std::string> split_property(const std::filesystem::path& spec) {
  const std::string file = spec.filename().string();
  const size_t hash = file.rfind('#');
  if (hash == std::string::npos) return {spec, ""};
  std::filesystem::path path = spec.parent_path() / file.substr(0, hash);
  if (path.extension() != ".ply") return {spec, ""};
  return {path, file.substr(hash + 1)};
}

}  // namespace

std::vector<double> parse_vertex_weights(std::string_view text, const std::string& name,
                                         size_t stop_after) {
  std::vector<double> weights;
  size_t begin = 0;
  for (int line = 1; begin <= text.size() && weights.size() < stop_after; ++line) {
    size_t end = text.find('\n', begin);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view row = text.substr(begin, end - begin);
    size_t pos = 0;
    for (std::string_view token = next_token(row, pos);
         !token.empty() && weights.size() < stop_after; token = next_token(row, pos)) {
      double w = 0.0;
      const std::string where = name + ":" + std::to_string(line) + ": ";
      if (!parse_double(token, w))
        throw InputError(where + "'" + std::string(token) + "' is not a number");
      if (!(w >= 0.0 && w <= 1.0))
        throw InputError(where + "weight " + std::string(token) +
                         " is not a number in [0, 1] (vertex " + std::to_string(weights.size()) +
                         ", 0-based)");
      weights.push_back(w);
    }
    begin = end + 1;
  }
  return weights;
}

std::vector<double> read_vertex_weights(const std::filesystem::path& spec, int vertices,
                                        const std::string& template_name) {
  const auto [path, property] = split_property(spec);
  const std::string name = path.string();
  std::vector<double> weights;
  const size_t wanted = static_cast<size_t>(std::max(vertices, 0));
  if (property.empty()) {
    // One number past the vertex count is enough to refuse the file: the rest is not parsed.
    weights = parse_vertex_weights(read_file(path), name, wanted + 1);
    if (weights.size() > wanted)
      throw InputError("massage.vertex_weights: " + spec.string() + " has more than " +
                       std::to_string(wanted) + " weights, but the template, " + template_name +
                       ", has " + std::to_string(vertices) + " vertices");
  } else {
    PlyVertexProperty values{property, {}};
    parse_ply(read_file(path), name, nullptr, &values);
    for (size_t i = 0; i < values.values.size(); ++i)
      if (const double w = values.values[i]; !(w >= 0.0 && w <= 1.0))
        throw InputError(name + ": vertex " + std::to_string(i) + ": " + property + " = " +
                         number_text(w) + " is not a weight in [0, 1]");
    weights = std::move(values.values);
  }
  if (static_cast<int>(weights.size()) != vertices)
    throw InputError("massage.vertex_weights: " + spec.string() + " has " +
                     std::to_string(weights.size()) + " weights, but the template, " +
                     template_name + ", has " + std::to_string(vertices) + " vertices");
  return weights;
}

}  // namespace sm
