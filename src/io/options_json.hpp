#pragma once
/// Options structs as JSON, through their tables (core/options_table.hpp). Reading is strict and
/// every message names the key by its JSON path: an unknown key (with the nearest known key for
/// a typo), a wrong type, a value out of range, a missing required key, e.g.
/// `massage.iterations: expected an integer >= 1, got "ten"`. Writing gives every key, so that
/// reading the result gives the same options back.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/options_table.hpp"

namespace sm {

/// Reads the JSON object `value` at `path` ("" = the document's top level) into `entries`: keys
/// left out keep their value; relative paths are made absolute against `base`. Throws
/// ConfigError "<path>: <what>" on the first problem.
void read_object(const nlohmann::json& value, const std::string& path, const Entries& entries,
                 const std::filesystem::path& base);

/// Reads one value into `entry` (`siblings`: the other keys of its object, for bounds by key).
void read_value(const nlohmann::json& value, const std::string& path, const Entry& entry,
                const Entries& siblings, const std::filesystem::path& base);

/// Every key of `entries` that is written (a key whose table says when, an empty path and an
/// absent optional object are left out).
nlohmann::json write_object(const Entries& entries);

/// One value as JSON; nothing for a key left out (an empty path, an absent optional object).
std::optional<nlohmann::json> write_value(const Entry& entry);

template <class S>
void read_options(const nlohmann::json& value, S& options, const std::filesystem::path& base,
                  const std::string& path = "") {
  read_object(value, path, entries_of(options), base);
}

template <class S>
nlohmann::json write_options(const S& options) {
  S copy = options;  // entries_of gives write access; writing only reads
  return write_object(entries_of(copy));
}

/// Throws ConfigError "<path>: <what>" ("config: <what>" for the top level).
[[noreturn]] void fail_at(const std::string& path, const std::string& what);

/// A JSON value for a message: its text (at most 60 characters), "an object" or "an array".
std::string describe(const nlohmann::json& value);

/// Throws unless `value` is an object whose keys are all among `known`: "expected an object" or
/// "<path>.<key>: unknown key (did you mean ...?)".
void check_keys(const nlohmann::json& value, const std::string& path,
                const std::vector<std::string>& known);

/// The keys of an object of `entries`, in table order (an Inline group's where it sits).
std::vector<std::string> keys_of(const Entries& entries);

/// `path` + "." + `key` ("key" for the top level).
std::string join_path(const std::string& path, std::string_view key);

}  // namespace sm
