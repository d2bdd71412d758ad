#pragma once
/// Atomic output files: content goes to a temporary file beside the destination, which is renamed
/// over the destination only when complete, so a crash or kill never leaves a partial file.
#include <filesystem>
#include <string>
#include <string_view>

namespace sm {

/// Suffix of the temporary files; `remove_stale_temporaries` deletes leftovers carrying it.
inline constexpr std::string_view kTempSuffix = ".seqmassage-tmp";

/// Writes `content` to `path` atomically (temporary file, flush, fsync, rename). Creates missing
/// parent folders. Throws IoError naming the file and the system's reason.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// Reads a whole file. Throws IoError naming the file when it cannot be opened or read.
std::string read_file(const std::filesystem::path& path);

/// Deletes temporary files left in `dir` (not recursive) by an interrupted run; returns how many.
int remove_stale_temporaries(const std::filesystem::path& dir);

}  // namespace sm
