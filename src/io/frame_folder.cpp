#include "io/frame_folder.hpp"

#include <algorithm>
#include <string>
#include <system_error>

#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

unsigned char fold(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u >= 'A' && u <= 'Z' ? static_cast<unsigned char>(u - 'A' + 'a') : u;
}

// <0, 0, >0 as a is before, equivalent to or after b in natural order (without the byte tie-break).
int natural_compare(std::string_view a, std::string_view b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (is_digit(a[i]) && is_digit(b[j])) {
      while (i < a.size() && a[i] == '0') ++i;
      while (j < b.size() && b[j] == '0') ++j;
      size_t ei = i, ej = j;
      while (ei < a.size() && is_digit(a[ei])) ++ei;
      while (ej < b.size() && is_digit(b[ej])) ++ej;
      if (ei - i != ej - j) return ei - i < ej - j ? -1 : 1;  // fewer digits, smaller value
      const int c = a.substr(i, ei - i).compare(b.substr(j, ej - j));
      if (c != 0) return c;
      i = ei;
      j = ej;
    } else {
      const unsigned char ca = fold(a[i]), cb = fold(b[j]);
      if (ca != cb) return ca < cb ? -1 : 1;
      ++i;
      ++j;
    }
  }
  if (i < a.size()) return 1;
  if (j < b.size()) return -1;
  return 0;
}

bool ends_with_folded(std::string_view name, std::string_view suffix) {
  if (name.size() < suffix.size()) return false;
  const std::string_view tail = name.substr(name.size() - suffix.size());
  for (size_t k = 0; k < suffix.size(); ++k) {
    if (fold(tail[k]) != fold(suffix[k])) return false;
  }
  return true;
}

// What a directory entry that is not a regular file (nor a link to one) is, or "" if it is one.
std::string not_a_frame_file(const fs::directory_entry& entry) {
  std::error_code ec;
  const fs::file_status own = entry.symlink_status(ec);
  if (ec) return "unreadable (" + ec.message() + ")";
  const bool link = fs::is_symlink(own);
  const fs::file_status target = link ? fs::status(entry.path(), ec) : own;
  if (link && ec) {
    std::error_code read_ec;
    const fs::path to = fs::read_symlink(entry.path(), read_ec);
    const std::string where = read_ec ? "" : " (to '" + to.string() + "')";
    if (ec == std::errc::too_many_symbolic_link_levels) return "a symbolic link loop" + where;
    if (ec == std::errc::no_such_file_or_directory) return "a dangling symbolic link" + where;
    return "a symbolic link that cannot be followed" + where + ": " + ec.message();
  }
  const std::string via = link ? "a symbolic link to " : "";
  switch (target.type()) {
    case fs::file_type::regular:
      return "";
    case fs::file_type::directory:
      return via + "a folder";
    case fs::file_type::fifo:
      return via + "a FIFO (named pipe)";
    case fs::file_type::socket:
      return via + "a socket";
    case fs::file_type::character:
      return via + "a character device";
    case fs::file_type::block:
      return via + "a block device";
    default:
      return via + "not a regular file";
  }
}

}  // namespace

bool natural_less(std::string_view a, std::string_view b) {
  const int c = natural_compare(a, b);
  return c != 0 ? c < 0 : a < b;
}

std::vector<fs::path> list_frames(const fs::path& dir, std::string_view extension) {
  std::string suffix(extension);
  if (suffix.empty() || suffix[0] != '.') suffix.insert(suffix.begin(), '.');
  std::error_code ec;
  const fs::file_status status = fs::status(dir, ec);
  if (status.type() == fs::file_type::not_found) {
    throw IoError("frame folder '" + dir.string() + "' does not exist");
  }
  if (ec) throw IoError("cannot access frame folder '" + dir.string() + "': " + ec.message());
  if (!fs::is_directory(status)) {
    throw InputError("frame folder '" + dir.string() + "' is not a folder");
  }
  std::vector<std::pair<std::string, fs::path>> frames;
  std::vector<std::pair<std::string, std::string>> bad;  // (name, what it is)
  fs::directory_iterator it(dir, ec);
  for (const fs::directory_iterator end; !ec && it != end; it.increment(ec)) {
    std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.' || name.size() == suffix.size() ||
        !ends_with_folded(name, suffix)) {
      continue;
    }
    // Skipped, it would renumber the frames after it (template.frame, --frames, shard blocks).
    if (std::string kind = not_a_frame_file(*it); !kind.empty()) {
      bad.emplace_back(std::move(name), std::move(kind));
      continue;
    }
    frames.emplace_back(std::move(name), it->path());
  }
  if (ec) throw IoError("cannot list frame folder '" + dir.string() + "': " + ec.message());
  if (!bad.empty()) {  // the first in natural order, whatever order the folder lists them in
    const auto first = std::min_element(bad.begin(), bad.end(), [](const auto& a, const auto& b) {
      return natural_less(a.first, b.first);
    });
    throw InputError("frame folder '" + dir.string() + "': '" + first->first + "' is " +
                     first->second + ", not a frame file; every " + suffix +
                     " entry must be a regular file (or a link to one): remove it or fix it" +
                     (bad.size() > 1 ? " (and " + std::to_string(bad.size() - 1) + " more)" : ""));
  }
  if (frames.empty()) {
    throw InputError("frame folder '" + dir.string() + "' has no " + suffix + " files");
  }
  std::sort(frames.begin(), frames.end(),
            [](const auto& a, const auto& b) { return natural_less(a.first, b.first); });
  std::vector<fs::path> paths;
  paths.reserve(frames.size());
  for (auto& f : frames) paths.push_back(std::move(f.second));
  return paths;
}

}  // namespace sm
