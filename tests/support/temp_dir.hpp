#pragma once
/// A fresh folder under the system's temporary folder for one test, removed with everything in it
/// when the test ends.
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>

namespace sm::test {

class TempDir {
 public:
  /// `name` only makes the folder recognizable; the process id and a counter make it unique.
  explicit TempDir(const std::string& name = "test") {
    static std::atomic<int> counter{0};
    path_ =
        std::filesystem::temp_directory_path() /
        ("seqmassage-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& child) const { return path_ / child; }

 private:
  std::filesystem::path path_;
};

}  // namespace sm::test
