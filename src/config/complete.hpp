#pragma once
/// A config with every key spelled out (`seqmassage config --complete FILE`): the keys the file
/// gives keep their values as written (relative paths stay relative) and their order; every other
/// key its job resolves is added at its default, after the given ones of its object. This is how
/// configs/*_all_keys.json are written, so a new key reaches them from its table line.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace sm {

/// `text` (a config file's contents) checked as load_any_config checks it, relative paths against
/// `base_dir`, and completed; ConfigError as load_any_config's.
nlohmann::ordered_json complete_config(const std::string& text,
                                       const std::filesystem::path& base_dir);

/// The completed config of the file at `path`, as the file it should be: JSON indented by 2
/// (an array of numbers or strings on one line), with a final newline.
std::string complete_config_file(const std::filesystem::path& path);

}  // namespace sm
