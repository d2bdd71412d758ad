#pragma once
/// What value a key of an options table takes, described once as data: its type's name, the
/// JSON types it admits, whether the table's interval bounds it, and what it accepts in words.
/// The reference (`seqmassage config --reference`), the Python `massage_keys()` /
/// `measure_keys()` and through them the Blender panel all read this; none of them inspects the
/// member's type or parses another's prose. (The JSON reader dispatches on the member's type
/// itself, because it writes the member; its messages use the same words, describe_integers and
/// describe_numbers.)
#include <string>
#include <string_view>

#include "core/options_table.hpp"

namespace sm {

/// Every KeyType::name, in the order the kinds are listed in the docs.
inline constexpr std::string_view kKeyTypeNames[] = {
    "boolean",      "integer",     "number",     "integer_or_none", "number_or_none",
    "number_or_auto", "integer_list", "number_list", "choice",        "path",
    "frames",       "selector",    "toggle",     "object"};

struct KeyType {
  std::string_view name;  ///< one of kKeyTypeNames
  std::string_view json;  ///< the JSON types it admits, as the reference says them
  bool bounded = false;   ///< the spec's [lo, hi] applies (to the value, or to each item)
  bool nullable = false;  ///< null (None) is a value: "no value"
  std::string accepts;    ///< what it accepts, plain text ("an integer >= 1"), null left out
  std::string allowed;    ///< the same in Markdown for the reference's "allowed" cell, null said
};

/// The type of table entry `e` (its member's type with its ValueSpec).
KeyType key_type(const Entry& e);

}  // namespace sm
