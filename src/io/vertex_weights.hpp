#pragma once
/// Per-vertex weights from a file (the "massage.vertex_weights" key): a text file of numbers, or a
/// scalar vertex property of a PLY file, one value in [0, 1] per vertex of the template.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sm {

/// Parses text weights: numbers separated by blanks or line breaks, any number per line; `name`
/// prefixes messages. Throws InputError "name:line: ..." for a token that is not a number or a
/// value that is not finite or outside [0, 1]. Stops after `stop_after` numbers: what follows is
/// not parsed (a reader that knows the count asks for one more, to see that there are too many).
std::vector<double> parse_vertex_weights(std::string_view text, const std::string& name,
                                         size_t stop_after = SIZE_MAX);

/// Reads `spec`: "file.ply#name" (the PLY vertex property `name`, any scalar type) or any other
/// path (a text file, parse_vertex_weights, which stops at the first number past `vertices`).
/// Throws InputError naming the file if the count is not `vertices` (the template's, named `template_name`), or for a value outside [0, 1] (naming the
/// line, or the vertex for PLY); IoError if the file cannot be read.
std::vector<double> read_vertex_weights(const std::filesystem::path& spec, int vertices,
                                        const std::string& template_name);

}  // namespace sm
