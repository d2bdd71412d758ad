#pragma once
/// The inputs a run must never overwrite: every file it reads, compared by identity (device and
/// inode, links resolved) with every file it will write, so that an input saved inside the output
/// folder (a config saved as out/report.json, weights as out/summary.csv, a hard link) is refused
/// at planning, before anything is written.
#include <filesystem>
#include <string>
#include <vector>

namespace sm {

/// A file the run reads, and what it is for the message ("config", "template.mesh", ...).
struct ReadFile {
  std::string what;
  std::filesystem::path path;
};

/// Throws ConfigError "output.dir: writing <output> would overwrite an input file, <what>
/// '<input>' (the same file); ..." for the first of `outputs` that is one of `inputs`: the same device and inode
/// (after resolving links), or, for a file not there yet, the same resolved path.
void refuse_overwriting_inputs(const std::vector<ReadFile>& inputs,
                               const std::vector<std::filesystem::path>& outputs);

/// The file a "vertex_weights" value names: "w.ply#quality" reads w.ply.
std::filesystem::path weights_file_read(const std::filesystem::path& spec);

}  // namespace sm
