#include "io/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <random>
#include <vector>

#include "io/input_file.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what, const fs::path& path, int err) {
  throw IoError(what + " '" + path.string() + "': " + std::strerror(err));
}

fs::path normal_absolute(const fs::path& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  if (ec) a = p;
  a = a.lexically_normal();
  if (!a.has_filename() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
  return a;
}

// The declared output folders (OutputFolder), by absolute normal path.
struct Declared {
  const OutputFolder* folder;
};
std::mutex& declared_mutex() {
  static std::mutex m;
  return m;
}
std::vector<Declared>& declared() {
  static std::vector<Declared> list;
  return list;
}

struct Root {
  int fd = -1;      // a duplicate of the output folder's descriptor
  fs::path path;    // the output folder
  fs::path below;   // the folder asked for, relative to it ("." for itself)
};

// The declared output folder holding `dir` (the deepest one); fd -1 if `dir` is in none.
Root declared_root(const fs::path& dir) {
  const fs::path wanted = normal_absolute(dir);
  std::lock_guard<std::mutex> guard(declared_mutex());
  const OutputFolder* best = nullptr;
  fs::path below;
  for (const Declared& d : declared()) {
    const fs::path rel = wanted.lexically_relative(d.folder->path());
    if (rel.empty() || *rel.begin() == "..") continue;
    if (!best || d.folder->path().native().size() > best->path().native().size()) {
      best = d.folder;
      below = rel;
    }
  }
  if (!best) return {};
  const int fd = ::fcntl(best->fd(), F_DUPFD_CLOEXEC, 0);
  if (fd < 0) fail("cannot open folder", best->path(), errno);
  return {fd, best->path(), below};
}

// Opens folder `dir` for creating files in it. Below a declared output folder, walks down from
// it, creating missing folders if `create`, opening each with O_NOFOLLOW|O_DIRECTORY, and refuses
// a symbolic link. Elsewhere (a path the user named, e.g. `measure --csv`), opens it as given.
// Returns -1 (errno ENOENT) if it does not exist and !create.
int open_folder(const fs::path& given, bool create) {
  const fs::path dir = given.empty() ? fs::path(".") : given;
  Root root = declared_root(dir);
  int fd = root.fd;
  if (fd < 0) {
    std::error_code ec;
    if (create) {
      fs::create_directories(dir, ec);
      if (ec) throw IoError("cannot create folder '" + dir.string() + "': " + ec.message());
    }
    const int opened =
        ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (opened < 0 && !(errno == ENOENT && !create)) fail("cannot open folder", dir, errno);
    return opened;
  }
  fs::path at = root.path;
  for (const fs::path& part : root.below) {
    if (part == "." || part.empty()) continue;
    at /= part;
    int next = ::openat(fd, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (next < 0 && errno == ENOENT && create) {
      if (::mkdirat(fd, part.c_str(), 0777) != 0 && errno != EEXIST) {
        const int err = errno;
        ::close(fd);
        fail("cannot create folder", at, err);
      }
      next = ::openat(fd, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    }
    if (next < 0) {
      const int err = errno;
      struct stat st {};
      const bool link =
          ::fstatat(fd, part.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(st.st_mode);
      ::close(fd);
      if (link)
        throw IoError("refusing to write into '" + at.string() +
                      "': it is a symbolic link, and a folder inside the output folder must be a "
                      "real folder (remove the link, then run again)");
      if (err == ENOENT && !create) {
        errno = ENOENT;
        return -1;
      }
      fail(create ? "cannot create folder" : "cannot open folder", at, err);
    }
    ::close(fd);
    fd = next;
  }
  return fd;
}

// 16 hex digits no other process can predict (getrandom; std::random_device where it fails).
std::string random_hex() {
  uint64_t value = 0;
  if (::getrandom(&value, sizeof value, 0) != ssize_t(sizeof value)) {
    std::random_device device;
    value = (uint64_t(device()) << 32) ^ device();
  }
  static const char digits[] = "0123456789abcdef";
  std::string text(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) text[size_t(i)] = digits[value & 15];
  return text;
}

}  // namespace

OutputFolder::OutputFolder(const fs::path& dir) : key_(normal_absolute(dir)) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw IoError("cannot create folder '" + dir.string() + "': " + ec.message());
  fd_ = ::open(key_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) fail("cannot open folder", dir, errno);
  std::lock_guard<std::mutex> guard(declared_mutex());
  declared().push_back({this});
}

OutputFolder::~OutputFolder() {
  {
    std::lock_guard<std::mutex> guard(declared_mutex());
    auto& list = declared();
    list.erase(std::remove_if(list.begin(), list.end(),
                              [this](const Declared& d) { return d.folder == this; }),
               list.end());
  }
  if (fd_ >= 0) ::close(fd_);
}

AtomicFileWriter::AtomicFileWriter(const fs::path& path) : path_(path) {
  name_ = path.filename().string();
  if (name_.empty() || name_ == "." || name_ == "..")
    throw IoError("cannot write '" + path.string() + "': not a file name");
  dir_fd_ = open_folder(path.parent_path(), true);
  // Created exclusively under a name nobody can guess: a link or file planted beside the
  // destination is never opened (O_EXCL fails on any existing name, O_NOFOLLOW on a link).
  const std::string stem = name_ + "." + temporary_owner() + ".";
  for (int attempt = 0; fd_ < 0; ++attempt) {
    tmp_name_ = stem + random_hex() + std::string(kTempSuffix);
    fd_ = ::openat(dir_fd_, tmp_name_.c_str(),
                   O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd_ < 0 && (errno != EEXIST || attempt >= 100)) {
      const int err = errno;
      ::close(dir_fd_);
      dir_fd_ = -1;
      fail("cannot create", path.parent_path() / tmp_name_, err);
    }
  }
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlinkat(dir_fd_, tmp_name_.c_str(), 0);
  }
  if (dir_fd_ >= 0) ::close(dir_fd_);
}

void AtomicFileWriter::abandon(const char* what, int err) {
  ::close(fd_);
  fd_ = -1;
  ::unlinkat(dir_fd_, tmp_name_.c_str(), 0);
  fail(what, path_, err);
}

void AtomicFileWriter::write(std::string_view content) {
  if (fd_ < 0) throw std::logic_error("AtomicFileWriter::write after commit");
  const char* p = content.data();
  size_t left = content.size();
  while (left > 0) {
    const ssize_t w = ::write(fd_, p, left);
    if (w < 0) {
      if (errno == EINTR) continue;
      abandon("cannot write", errno);
    }
    p += w;
    left -= static_cast<size_t>(w);
  }
}

void AtomicFileWriter::commit() {
  if (fd_ < 0) throw std::logic_error("AtomicFileWriter::commit twice");
  if (::fsync(fd_) != 0 && errno != EINVAL) abandon("cannot flush", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlinkat(dir_fd_, tmp_name_.c_str(), 0);
    fail("cannot close", path_, err);
  }
  // Relative to the folder held open: a link at the destination is replaced, not followed.
  if (::renameat(dir_fd_, tmp_name_.c_str(), dir_fd_, name_.c_str()) != 0) {
    const int err = errno;
    ::unlinkat(dir_fd_, tmp_name_.c_str(), 0);
    fail("cannot rename temporary file onto", path_, err);
  }
}

void write_file_atomic(const fs::path& path, std::string_view content) {
  AtomicFileWriter file(path);
  file.write(content);
  file.commit();
}

void remove_output_file(const fs::path& path) {
  const std::string name = path.filename().string();
  if (name.empty() || name == "." || name == "..") return;
  const int dir = open_folder(path.parent_path(), false);
  if (dir < 0) return;  // no folder, no file
  const int removed = ::unlinkat(dir, name.c_str(), 0);
  const int err = errno;
  ::close(dir);
  if (removed != 0 && err != ENOENT) fail("cannot remove", path, err);
}

std::string read_file(const fs::path& path) {
  return read_input_file(path);
}

namespace {

std::string host_name() {
  char buffer[256] = {};
  if (::gethostname(buffer, sizeof buffer - 1) != 0 || buffer[0] == '\0') return "localhost";
  std::string host = buffer;
  for (char& c : host)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return host;
}

bool all_digits(std::string_view s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos;
}

// Whether the writer named in a temporary file's name (see write_file_atomic) is gone: a process
// of this host that no longer runs. Names of other hosts, or that do not parse, are not judged.
// The part before the suffix is random hex digits (a counter in older versions).
bool writer_is_gone(std::string_view name, const std::string& host) {
  name.remove_suffix(kTempSuffix.size());
  const size_t counter = name.rfind('.');
  if (counter == std::string_view::npos || name.size() == counter + 1 ||
      name.substr(counter + 1).find_first_not_of("0123456789abcdef") != std::string_view::npos)
    return false;
  name = name.substr(0, counter);
  const size_t tag = name.rfind('.');
  if (tag == std::string_view::npos) return false;
  const std::string_view owner = name.substr(tag + 1);  // "<host>-<pid>", or "<pid>" (older)
  const size_t dash = owner.rfind('-');
  const std::string_view pid = dash == std::string_view::npos ? owner : owner.substr(dash + 1);
  if (dash != std::string_view::npos && owner.substr(0, dash) != host) return false;
  if (!all_digits(pid) || pid.size() > 9) return false;
  const long id = std::stol(std::string(pid));
  if (id == static_cast<long>(::getpid())) return false;
  return ::kill(static_cast<pid_t>(id), 0) != 0 && errno == ESRCH;
}

}  // namespace

std::string temporary_owner() {
  static const std::string host = host_name();
  return host + "-" + std::to_string(::getpid());  // not cached: a forked child has its own pid
}

int remove_stale_temporaries(const fs::path& dir) {
  const std::string host = host_name();
  int fd = -1;
  try {
    fd = open_folder(dir, false);
  } catch (const IoError&) {
    return 0;  // a link in place of a folder: not ours to clean (writing there is refused)
  }
  if (fd < 0) return 0;
  DIR* listing = ::fdopendir(fd);
  if (!listing) {
    ::close(fd);
    return 0;
  }
  std::vector<std::string> stale;
  while (const dirent* entry = ::readdir(listing)) {
    const std::string name = entry->d_name;
    if (name.size() > kTempSuffix.size() &&
        name.compare(name.size() - kTempSuffix.size(), kTempSuffix.size(), kTempSuffix) == 0 &&
        writer_is_gone(name, host))
      stale.push_back(name);
  }
  int removed = 0;
  for (const std::string& name : stale) removed += ::unlinkat(::dirfd(listing), name.c_str(), 0) == 0;
  ::closedir(listing);
  return removed;
}

}  // namespace sm
