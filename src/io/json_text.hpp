#pragma once
/// The config file's text: strict JSON (the mapping onto the jobs' options is config/config.hpp).
#include <string_view>

#include <nlohmann/json.hpp>

namespace sm {

/// Parses JSON text strictly: no comments, no duplicate keys, no trailing content, no NUL byte,
/// no nesting deeper than 64 levels. Throws ConfigError "line L, column C: <reason>" (or "<path>:
/// duplicate key ...", "<path>: nested deeper than 64 levels") on the first problem. Memory is
/// linear in the text (JSON paths are built only for a message).
nlohmann::json parse_json_strict(std::string_view text);

}  // namespace sm
