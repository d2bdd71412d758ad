#pragma once
/// Opening input files safely: without blocking (a FIFO must not hang a run) and only when they are
/// regular files (a symlink to /dev/zero must not be read without end), with errors naming them.
#include <cstdint>
#include <filesystem>
#include <string>

namespace sm {

/// An input file opened read-only with O_NONBLOCK and checked by fstat to be a regular file; the
/// descriptor is closed when this goes out of scope. Reads block normally afterwards (O_NONBLOCK
/// only matters to the open of a FIFO or a device, which are refused before any read).
class InputFile {
 public:
  /// Throws IoError when `path` cannot be opened or is a folder ("cannot read '<path>': Is a
  /// directory"), InputError when it is another kind of file ("'<path>': not a regular file (a
  /// FIFO); only regular files are read").
  explicit InputFile(const std::filesystem::path& path);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  /// Size in bytes reported by fstat when the file was opened.
  uint64_t size() const { return size_; }
  /// Reads up to `n` bytes into `buffer`; returns how many, 0 at the end. Throws IoError.
  size_t read(char* buffer, size_t n);
  /// The whole content, reading until the end (a file that grows meanwhile is read as it is).
  std::string read_all();

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

/// Reads a whole input file (InputFile::read_all). Throws as InputFile.
std::string read_input_file(const std::filesystem::path& path);

/// Checks without opening it for long that `path` is a regular file (through symlinks): throws
/// as InputFile. Used for files handed to code that opens them itself.
void check_input_file(const std::filesystem::path& path);

/// "a FIFO", "a character device", "a folder", ... : what a file of mode `st_mode` is, for messages.
std::string describe_file_kind(unsigned st_mode);

}  // namespace sm
