#pragma once
/// Atomic output files: content goes to a temporary file beside the destination, which is renamed
/// over the destination only when complete, so a crash or kill never leaves a partial file.
///
/// Output folders others can write to: a temporary file is created exclusively (O_EXCL,
/// O_NOFOLLOW) under an unpredictable name, in a folder held open, and renamed relative to it
/// (renameat), so a link planted at its name or at the destination is never followed (the
/// destination is replaced, like any file). Below a folder declared with OutputFolder (a run's
/// output folder, while its lock is held), every sub-folder is opened with O_NOFOLLOW and
/// O_DIRECTORY from the output folder down: a symbolic link in its place is refused (IoError).
#include <filesystem>
#include <string>
#include <string_view>

namespace sm {

/// Suffix of the temporary files; `remove_stale_temporaries` deletes leftovers carrying it.
inline constexpr std::string_view kTempSuffix = ".seqmassage-tmp";

/// Writes `content` to `path` atomically (temporary file, flush, fsync, rename). Creates missing
/// parent folders. Throws IoError naming the file and the system's reason. The temporary file is
/// `<path>.<host>-<pid>.<random>.seqmassage-tmp` (16 random hex digits), created exclusively:
/// unpredictable, and naming its writer, so that processes sharing an output folder (shards) never
/// touch each other's.
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

  std::filesystem::path path_;
  std::string name_, tmp_name_;  // in dir_fd_
  int dir_fd_ = -1, fd_ = -1;
};

/// Removes the file `path` (nothing if it does not exist; a link is removed, not followed), through
/// the same folders write_file_atomic would write it through. Throws IoError as it does.
void remove_output_file(const std::filesystem::path& path);

/// Declares `dir` (created if missing) an output folder for the object's lifetime: files written
/// below it go through sub-folders opened without following links (see the header). `dir`
/// itself is opened as configured (a link there is the user's own). Held by OutputLock.
class OutputFolder {
 public:
  explicit OutputFolder(const std::filesystem::path& dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  /// The folder, opened (O_DIRECTORY) when declared.
  int fd() const { return fd_; }
  const std::filesystem::path& path() const { return key_; }

 private:
  std::filesystem::path key_;  // absolute, normal
  int fd_ = -1;
};

/// Reads a whole file. Throws IoError naming the file when it cannot be opened or read.
std::string read_file(const std::filesystem::path& path);

/// "<host>-<pid>" of this process (the host name with characters other than letters, digits,
/// '-' and '_' replaced by '_'): the writer tag in temporary file names.
std::string temporary_owner();

/// Deletes the temporary files in `dir` (not recursive) that a process of this host left when it
/// was killed: those whose writer process no longer runs (a live writer, e.g. another shard, is
/// left alone, and so are other hosts' files, which no run ever reads). Returns how many. A `dir`
/// below an output folder is opened as write_file_atomic opens it; a link there is left alone.
int remove_stale_temporaries(const std::filesystem::path& dir);

}  // namespace sm
