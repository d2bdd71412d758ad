#include "pipeline/cluster/output_lock.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <optional>
#include <regex>
#include <thread>

#include "io/atomic_file.hpp"
#include "core/errors.hpp"

namespace sm {
namespace fs = std::filesystem;

namespace {

std::string this_host() {
  char buffer[256] = {};
  if (::gethostname(buffer, sizeof buffer - 1) != 0 || buffer[0] == '\0') return "localhost";
  return buffer;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string read_all(int fd) {
  std::string text;
  char buffer[512];
  for (off_t at = 0; text.size() < 4096;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, at);
    if (n <= 0) break;
    text.append(buffer, size_t(n));
    at += n;
  }
  return text;
}

// "host H\npid P\nstarted T\n"; nullopt if it names no holder (empty, being written, foreign).
std::optional<LockHolder> parse_holder(const std::string& text) {
  static const std::regex pattern(R"(host ([^\n]+)\npid (\d{1,9})\n(?:started ([^\n]*)\n)?)");
  std::smatch m;
  if (!std::regex_search(text, m, pattern)) return std::nullopt;
  return LockHolder{m[1].str(), std::stol(m[2].str()), m[3].str()};
}

std::optional<LockHolder> holder_of(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return std::nullopt;
  std::optional<LockHolder> h = parse_holder(read_all(fd));
  ::close(fd);
  return h;
}

// Whether `fd` is still the file at `path` (a holder that ends removes its file while it holds the
// lock; a process that opened the old file before must start again with the new one).
bool is_current(int fd, const fs::path& path) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::lstat(path.c_str(), &b) == 0 && a.st_nlink > 0 &&
         a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

// The holders of the folder's shard lock files, "shard 1/4 (host H, pid P, since T)", for the
// message when the folder's lock is held shared by shards.
std::string shard_holders(const fs::path& dir) {
  static const std::regex pattern(R"(\.seqmassage-shard-(\d+)-of-(\d+)\.lock)");
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    names.push_back(it->path().filename().string());
  std::sort(names.begin(), names.end());
  std::string list;
  for (const std::string& name : names) {
    std::smatch m;
    if (!std::regex_match(name, m, pattern)) continue;
    const std::optional<LockHolder> h = holder_of(dir / name);
    list += std::string(list.empty() ? "" : ", ") + "shard " + m[1].str() + "/" + m[2].str() +
            " (" + (h ? h->text() : "holder not named") + ", " + name + ")";
  }
  return list;
}

[[noreturn]] void refuse(const fs::path& dir, const fs::path& file, bool exclusive) {
  const std::optional<LockHolder> h = holder_of(file);
  std::string who;
  if (h)
    who = h->text();
  else if (exclusive && file.filename() == lock_file_name({}))
    who = "the shards running there: " + shard_holders(dir);
  if (who.empty() || who == "the shards running there: ") who = "another process (not named yet)";
  throw IoError("output folder '" + dir.string() + "' is in use: its lock file '" + file.string() +
                "' is held by " + who +
                "; one writer per output folder (and shard): wait until that run ends, or stop "
                "it, then run again");
}

bool locks_unsupported(int error) {
  return error == ENOLCK || error == EOPNOTSUPP || error == ENOSYS || error == EINVAL;
}

}  // namespace

std::string LockHolder::text() const {
  return "host " + host + ", pid " + std::to_string(pid) +
         (started.empty() ? "" : ", since " + started);
}

std::string lock_file_name(const ShardOptions& shard) {
  if (!shard.sharded()) return ".seqmassage.lock";
  return ".seqmassage-shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) +
         ".lock";
}

namespace {

// Opens and flocks `file` (exclusive or shared), retrying while another holder removes it or
// holds it for a moment. Returns the descriptor; throws IoError when it stays held.
// The lock file is opened in the output folder held open (openat), never through a link, and
// refused when it has other names (a hard link planted there would make its truncation and
// rewriting another file's).
int take(const fs::path& dir, int dir_fd, const fs::path& file, bool exclusive,
         bool& unsupported) {
  const std::string name = file.filename().string();
  for (int attempt = 0;; ++attempt) {
    const int fd = ::openat(dir_fd, name.c_str(),
                            O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    if (fd < 0)
      throw IoError("cannot create the lock file '" + file.string() + "': " + std::strerror(errno) +
                    (errno == ELOOP ? " (it is a symbolic link: remove it)" : ""));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      throw IoError("lock file '" + file.string() + "' is not a regular file: remove it");
    }
    if (st.st_nlink > 1) {
      ::close(fd);
      throw IoError("lock file '" + file.string() + "' has " + std::to_string(st.st_nlink) +
                    " links (another name for the same file exists, a hard link): refusing to "
                    "write it; remove it");
    }
    if (::flock(fd, (exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB) == 0) {
      if (is_current(fd, file)) return fd;
    } else if (locks_unsupported(errno)) {
      unsupported = true;
      return fd;
    } else if (errno != EWOULDBLOCK && errno != EINTR) {
      const int error = errno;
      ::close(fd);
      throw IoError("cannot lock '" + file.string() + "': " + std::strerror(error));
    } else if (attempt >= 10 && is_current(fd, file)) {
      ::close(fd);
      refuse(dir, file, exclusive);
    }
    ::close(fd);
    if (attempt > 50) throw IoError("cannot lock '" + file.string() + "': it keeps changing");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

OutputLock lock_output_folder(const fs::path& dir, const ShardOptions& shard) {
  const std::string host = this_host();
  const long self = static_cast<long>(::getpid());
  OutputLock lock;
  lock.folder_ = std::make_unique<OutputFolder>(dir);  // created if missing
  std::vector<std::pair<fs::path, bool>> wanted = {{dir / lock_file_name({}), !shard.sharded()}};
  if (shard.sharded()) wanted.emplace_back(dir / lock_file_name(shard), true);
  for (const auto& [file, exclusive] : wanted) {
    bool unsupported = false;
    const int fd = take(dir, lock.folder_->fd(), file, exclusive, unsupported);
    const std::optional<LockHolder> before = parse_holder(read_all(fd));
    if (unsupported) {
      // No flock here (some network file systems): the content is all there is to judge by.
      if (before && !(before->host == host && before->pid == self) &&
          (before->host != host || ::kill(pid_t(before->pid), 0) == 0 || errno == EPERM)) {
        ::close(fd);
        refuse(dir, file, exclusive);
      }
      if (!exclusive) {  // a shared lock that cannot be held: the shard's own lock still guards
        ::close(fd);
        continue;
      }
    }
    lock.held_.push_back({fd, file, exclusive});
    if (before && !(before->host == host && before->pid == self))
      lock.warnings_.push_back("took over the lock file '" + file.string() + "' left by " +
                               before->text() +
                               ": that run ended without removing it (killed, or its host "
                               "went down)");
    const std::string text = exclusive ? "host " + host + "\npid " + std::to_string(self) +
                                             "\nstarted " + utc_now() + "\n"
                                       : "";
    if (::ftruncate(fd, 0) != 0 ||
        (!text.empty() && ::pwrite(fd, text.data(), text.size(), 0) != ssize_t(text.size()))) {
      const int error = errno;
      throw IoError("cannot write the lock file '" + file.string() + "': " + std::strerror(error));
    }
  }
  return lock;
}

OutputLock::OutputLock(OutputLock&& other) noexcept
    : held_(std::move(other.held_)),
      warnings_(std::move(other.warnings_)),
      folder_(std::move(other.folder_)) {
  other.held_.clear();
}

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    release();
    held_ = std::move(other.held_);
    warnings_ = std::move(other.warnings_);
    folder_ = std::move(other.folder_);
    other.held_.clear();
  }
  return *this;
}

OutputLock::~OutputLock() {
  release();
}

void OutputLock::release() {
  // The shard's own lock first, then the folder's: in reverse order of taking.
  for (auto it = held_.rbegin(); it != held_.rend(); ++it) {
    // A shared lock is removed by its last holder: the one that can make it exclusive.
    if (it->exclusive || ::flock(it->fd, LOCK_EX | LOCK_NB) == 0) {
      if (is_current(it->fd, it->file)) {
        if (folder_)
          ::unlinkat(folder_->fd(), it->file.filename().c_str(), 0);
        else
          ::unlink(it->file.c_str());
      }
    }
    ::close(it->fd);
  }
  held_.clear();
}

}  // namespace sm
