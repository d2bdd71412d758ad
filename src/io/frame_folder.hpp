#pragma once
/// Frame folders: the mesh files of a sequence, one per frame, in natural order of their names.
#include <filesystem>
#include <string_view>
#include <vector>

namespace sm {

/// Natural order of file names: runs of digits compare by value (frame_2 < frame_10, also for
/// several numbers: a2b10 > a2b9), other characters compare ASCII case-insensitively; names that
/// are equal this way (frame_02, frame_2; A, a) are ordered by their bytes. A strict weak order.
bool natural_less(std::string_view a, std::string_view b);

/// The regular files (or links to them) in `dir` whose names end with `extension` (with or without
/// the leading dot, case-insensitive), not recursively, sorted with natural_less on the file
/// names. Hidden files (names starting with '.', such as macOS "._frame_1.obj") are skipped.
/// Throws IoError if `dir` does not exist or cannot be listed, InputError if it is not a folder,
/// holds no matching file, or holds a matching entry that is not a regular file nor a link to
/// one (a dangling link, a link loop, a FIFO, a device, a folder: skipping it would renumber the
/// frames after it), naming the entry.
std::vector<std::filesystem::path> list_frames(const std::filesystem::path& dir,
                                               std::string_view extension = ".obj");

}  // namespace sm
