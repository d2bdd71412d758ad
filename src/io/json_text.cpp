#include "io/json_text.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.hpp"

namespace sm {
using json = nlohmann::json;

namespace {

/// Deepest nesting of arrays and objects in a config (its schema needs a handful): the parser's
/// stack, and so its memory, stays linear in the text.
constexpr int kConfigMaxDepth = 64;

// ---------------------------------------------------------------------------------------------
// Strict JSON: a SAX handler that builds the document, refuses duplicate keys and turns parse
// errors into a message instead of an exception.

class StrictBuilder {
 public:
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  explicit StrictBuilder(std::string_view text) : text_(text) {}

  bool null() { return put(json(nullptr)); }
  bool boolean(bool value) { return put(json(value)); }
  bool number_integer(number_integer_t value) { return put(json(value)); }
  bool number_unsigned(number_unsigned_t value) { return put(json(value)); }
  bool number_float(number_float_t value, const string_t&) { return put(json(value)); }
  bool string(string_t& value) { return put(json(value)); }
  bool binary(binary_t& value) { return put(json::binary(value)); }

  bool start_object(std::size_t) { return open(json::object()); }
  bool end_object() { return close(); }
  bool start_array(std::size_t) { return open(json::array()); }
  bool end_array() { return close(); }

  bool key(string_t& key) {
    Frame& top = stack_.back();
    if (top.value->contains(key)) {
      error_ = path_to(key) + ": duplicate key (each key may appear once)";
      return false;
    }
    top.key = key;
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& ex) {
    position_ = position;
    if (!last_token.empty() && last_token.back() == '/' && position < text_.size() &&
        (text_[position] == '/' || text_[position] == '*')) {
      error_ = "comments are not allowed in JSON";
      return false;
    }
    // "[json.exception.parse_error.101] parse error at line 3, column 5: <reason>" -> "<reason>",
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'" -> "number overflow ..."
    std::string what = ex.what();
    const size_t column = what.find("column ");
    const size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
    if (colon != std::string::npos) {
      what = what.substr(colon + 2);
    } else if (what.rfind("[json.exception.", 0) == 0 && what.find("] ") != std::string::npos) {
      what = what.substr(what.find("] ") + 2);
    }
    error_ = what;
    return false;
  }

  json& root() { return root_; }
  const std::string& error() const { return error_; }
  std::optional<size_t> position() const { return position_; }

 private:
  // One frame per open array or object: its value and the key being filled. JSON paths are built
  // only for a message (path_to), so memory stays linear in the depth.
  struct Frame {
    json* value;
    std::string key;
  };

  /// JSON path of the slot the parser fills next, with `key` appended (if not empty).
  std::string path_to(const std::string& key) const {
    std::string path;
    const auto append = [&](const std::string& k) { path += path.empty() ? k : "." + k; };
    for (const Frame& frame : stack_) {
      if (&frame == &stack_.back()) break;
      if (frame.value->is_array()) path += "[" + std::to_string(frame.value->size() - 1) + "]";
      else append(frame.key);
    }
    if (!key.empty()) append(key);
    return path;
  }

  // Inserts `value` where the parser is, returning its slot.
  json* insert(json value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Frame& top = stack_.back();
    if (top.value->is_array()) {
      top.value->push_back(std::move(value));
      return &top.value->back();
    }
    json& slot = (*top.value)[top.key];
    slot = std::move(value);
    return &slot;
  }
  bool put(json value) {
    insert(std::move(value));
    return true;
  }
  bool open(json container) {
    if (stack_.size() >= size_t(kConfigMaxDepth)) {
      std::string where;
      if (!stack_.empty()) {
        where = path_to(stack_.back().value->is_array() ? "" : stack_.back().key);
        if (stack_.back().value->is_array())
          where += "[" + std::to_string(stack_.back().value->size()) + "]";
      }
      error_ = (where.empty() ? std::string() : where + ": ") + "nested deeper than " +
               std::to_string(kConfigMaxDepth) + " levels";
      return false;
    }
    stack_.push_back({insert(std::move(container)), {}});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return true;
  }

  std::string_view text_;
  json root_;
  std::vector<Frame> stack_;
  std::string error_;
  std::optional<size_t> position_;
};

}  // namespace

namespace {

/// "line L, column C: " of byte `position` (1-based columns).
std::string line_and_column(std::string_view text, size_t position) {
  const size_t end = std::min(position, text.size());
  const std::string_view before = text.substr(0, end > 0 ? end - 1 : 0);
  const size_t line = 1 + std::count(before.begin(), before.end(), '\n');
  const size_t line_start = before.rfind('\n');
  const size_t column =
      before.size() - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
  return "line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";
}

}  // namespace

json parse_json_strict(std::string_view text) {
  // The JSON lexer takes a NUL byte for the end of the text and would ignore what follows; JSON
  // text never holds one (inside a string it must be written \u0000).
  if (const size_t nul = text.find('\0'); nul != std::string_view::npos) {
    throw ConfigError(line_and_column(text, nul + 1) +
                      "a NUL byte (JSON text cannot contain one; is this a binary file?)");
  }
  StrictBuilder builder(text);
  if (json::sax_parse(text, &builder, json::input_format_t::json, true, false))
    return std::move(builder.root());
  std::string where;
  if (auto position = builder.position()) where = line_and_column(text, *position);
  throw ConfigError(where + builder.error());
}

}  // namespace sm
