#pragma once
/// The configuration reference (`seqmassage config --reference`, docs/configuration.md): every key
/// of every job with its type, default, allowed values and meaning, generated from the options
/// tables, so that it cannot drift from what the reader accepts.
#include <string>

namespace sm {

/// The reference as Markdown.
std::string config_reference();

}  // namespace sm
