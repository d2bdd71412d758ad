#include "pipeline/sequence/input_clash.hpp"

#include <sys/stat.h>

#include <map>
#include <utility>

#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

fs::path resolved(const fs::path& p) {
  std::error_code ec;  // a path that cannot be resolved is compared as written
  const fs::path r = fs::weakly_canonical(p, ec);
  return (ec ? fs::absolute(p, ec) : r).lexically_normal();
}

}  // namespace

fs::path weights_file_read(const fs::path& spec) {
  const std::string name = spec.filename().string();
  const size_t hash = name.rfind('#');
  if (hash == std::string::npos) return spec;
  const fs::path file = spec.parent_path() / name.substr(0, hash);
  return file.extension() == ".ply" ? file : spec;
}

void refuse_overwriting_inputs(const std::vector<ReadFile>& inputs,
                               const std::vector<fs::path>& outputs) {
  std::map<std::pair<dev_t, ino_t>, const ReadFile*> by_identity;
  std::map<fs::path, const ReadFile*> by_path;
  for (const ReadFile& in : inputs) {
    if (in.path.empty()) continue;
    struct stat st {};
    if (::stat(in.path.c_str(), &st) == 0) by_identity.emplace(std::make_pair(st.st_dev, st.st_ino), &in);
    by_path.emplace(resolved(in.path), &in);
  }
  for (const fs::path& out : outputs) {
    const ReadFile* clash = nullptr;
    struct stat st {};
    if (::stat(out.c_str(), &st) == 0) {
      const auto it = by_identity.find({st.st_dev, st.st_ino});
      if (it != by_identity.end()) clash = it->second;
    }
    if (!clash) {
      const auto it = by_path.find(resolved(out));
      if (it != by_path.end()) clash = it->second;
    }
    if (clash)
      throw ConfigError("output.dir: writing " + out.string() +
                        " would overwrite an input file, " + clash->what + " '" +
                        clash->path.string() +
                        "' (the same file); choose another output folder, or move the input "
                        "out of it");
  }
}

}  // namespace sm
