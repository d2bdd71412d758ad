#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/input_file.hpp"
#include "mesh/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const std::string& what, const fs::path& path, int err) {
  throw IoError(what + " '" + path.string() + "': " + std::strerror(err));
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(const fs::path& path) : path_(path) {
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec)
      throw IoError("cannot create folder '" + path.parent_path().string() + "': " + ec.message());
  }
  // Unique per process and call, so concurrent writers of different files never collide.
  static std::atomic<unsigned long> counter{0};
  tmp_ = path;
  tmp_ += "." + temporary_owner() + "." + std::to_string(counter++) + std::string(kTempSuffix);
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) fail("cannot create", tmp_, errno);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(tmp_.c_str());
}

void AtomicFileWriter::abandon(const char* what, int err) {
  ::close(fd_);
  fd_ = -1;
  ::unlink(tmp_.c_str());
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
    ::unlink(tmp_.c_str());
    fail("cannot close", path_, err);
  }
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp_.c_str());
    fail("cannot rename temporary file onto", path_, err);
  }
}

void write_file_atomic(const fs::path& path, std::string_view content) {
  AtomicFileWriter file(path);
  file.write(content);
  file.commit();
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
bool writer_is_gone(std::string_view name, const std::string& host) {
  name.remove_suffix(kTempSuffix.size());
  const size_t counter = name.rfind('.');
  if (counter == std::string_view::npos || !all_digits(name.substr(counter + 1))) return false;
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
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > kTempSuffix.size() &&
        name.compare(name.size() - kTempSuffix.size(), kTempSuffix.size(), kTempSuffix) == 0 &&
        writer_is_gone(name, host)) {
      std::error_code rm;
      if (fs::remove(it->path(), rm)) ++removed;
    }
  }
  return removed;
}

}  // namespace sm
