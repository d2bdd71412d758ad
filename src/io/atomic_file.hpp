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
/// parent folders. Throws IoError naming the file and the system's reason. The temporary file is
/// `<path>.<host>-<pid>.<counter>.seqmassage-tmp`: unique per process and call, and naming its
/// writer, so that processes sharing an output folder (shards) never touch each other's.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// A file written atomically in pieces (for outputs too large to hold in memory): the content goes
/// to the temporary file write_file_atomic uses, which commit() renames over `path`. Destroyed
/// without commit() (an exception while writing), it removes the temporary file and leaves `path`
/// as it was. Throws IoError naming the file and the system's reason.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::filesystem::path& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void write(std::string_view content);
  /// Flushes, fsyncs and renames the temporary file onto the destination.
  void commit();

 private:
  [[noreturn]] void abandon(const char* what, int err);

  std::filesystem::path path_, tmp_;
  int fd_ = -1;
};

/// Reads a whole file. Throws IoError naming the file when it cannot be opened or read.
std::string read_file(const std::filesystem::path& path);

/// "<host>-<pid>" of this process (the host name with characters other than letters, digits,
/// '-' and '_' replaced by '_'): the writer tag in temporary file names.
std::string temporary_owner();

/// Deletes the temporary files in `dir` (not recursive) that a process of this host left when it
/// was killed: those whose writer process no longer runs (a live writer, e.g. another shard, is
/// left alone, and so are other hosts' files, which no run ever reads). Returns how many.
int remove_stale_temporaries(const std::filesystem::path& dir);

}  // namespace sm
