#pragma once
/// The config file's text: strict JSON (the mapping onto the jobs' options is config/config.hpp).
#include <string_view>

#include <nlohmann/json.hpp>

namespace sm {

/// Parses JSON text strictly: no comments, no duplicate keys, no trailing content. Throws
/// ConfigError "line L, column C: <reason>" (or "<path>: duplicate key ...") on the first problem.
nlohmann::json parse_json_strict(std::string_view text);

}  // namespace sm
