#include "io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail_input(const std::string& what, const fs::path& path, int err) {
  throw IoError(what + " '" + path.string() + "': " + std::strerror(err));
}

}  // namespace

std::string describe_file_kind(unsigned st_mode) {
  switch (st_mode & S_IFMT) {
    case S_IFREG:
      return "a regular file";
    case S_IFDIR:
      return "a folder";
    case S_IFIFO:
      return "a FIFO";
    case S_IFCHR:
      return "a character device";
    case S_IFBLK:
      return "a block device";
    case S_IFSOCK:
      return "a socket";
    default:
      return "not a file";
  }
}

InputFile::InputFile(const fs::path& path) : path_(path) {
  // O_NONBLOCK: opening a FIFO without a writer, or a device, returns at once instead of hanging.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) fail_input("cannot open", path, errno);
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int err = errno;
    ::close(fd_);
    fail_input("cannot read", path, err);
  }
  if (S_ISDIR(st.st_mode)) {  // as reading it would say
    ::close(fd_);
    fail_input("cannot read", path, EISDIR);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw InputError("'" + path.string() + "': not a regular file (" +
                     describe_file_kind(unsigned(st.st_mode)) + "); only regular files are read");
  }
  size_ = uint64_t(st.st_size);
  // Back to blocking reads: a regular file never blocks, and some file systems reject the flag.
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

size_t InputFile::read(char* buffer, size_t n) {
  for (;;) {
    const ssize_t r = ::read(fd_, buffer, n);
    if (r >= 0) return size_t(r);
    if (errno != EINTR) fail_input("cannot read", path_, errno);
  }
}

std::string InputFile::read_all() {
  std::string out;
  out.resize(size_t(size_));
  size_t have = 0;
  while (have < out.size()) {
    const size_t r = read(out.data() + have, out.size() - have);
    if (r == 0) break;
    have += r;
  }
  out.resize(have);
  if (have == size_) {  // the file may have grown since fstat: read the rest in blocks
    char block[1 << 16];
    while (const size_t r = read(block, sizeof block)) out.append(block, r);
  }
  return out;
}

std::string read_input_file(const fs::path& path) {
  return InputFile(path).read_all();
}

void check_input_file(const fs::path& path) {
  InputFile file(path);
}

}  // namespace sm
