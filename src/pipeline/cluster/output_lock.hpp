#pragma once
/// One writer per output folder: the lock files a run, a shard and `seqmassage merge` hold while
/// they write. A lock file is a small text file in the output folder naming its holder (host, pid,
/// start time) and held with flock(2) for the whole run, so the kernel (or, over NFS, the lock
/// manager) frees it when the holder ends, however it ends; the holder removes it when it is done.
///
/// - a whole run, a mesh job and merge hold `.seqmassage.lock` exclusively;
/// - shard I of N holds `.seqmassage-shard-I-of-N.lock` exclusively and `.seqmassage.lock` shared,
///   so the shards of one job run side by side, but not with a whole run or a merge of the folder.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/atomic_file.hpp"
#include "pipeline/sequence/shard.hpp"

namespace sm {

/// Who holds (or last held) a lock file: its content.
struct LockHolder {
  std::string host;
  long pid = 0;
  std::string started;       ///< UTC, ISO 8601
  std::string text() const;  ///< "host node1, pid 1234, since 2026-01-01T00:00:00Z"
};

/// ".seqmassage.lock" (the folder), or ".seqmassage-shard-I-of-N.lock" for a shard.
std::string lock_file_name(const ShardOptions& shard);

class OutputLock;

/// Takes the locks of a writer into `dir` (created if missing): for a shard (shard.sharded()) its
/// shard's lock and the folder's shared lock, otherwise the folder's exclusive lock. Throws
/// IoError when another process holds one, naming the lock file and its holder (host, pid, since
/// when; for the folder's lock held by shards, the shards' holders), or when the lock file cannot
/// be created or locked. A lock file left by a holder that ended is taken over (see warnings()).
/// The lock files are opened in the folder with O_NOFOLLOW, and one with another name (a hard
/// link) is refused. While the lock is held, `dir` is an OutputFolder: nothing written below it
/// follows a link (io/atomic_file.hpp).
OutputLock lock_output_folder(const std::filesystem::path& dir, const ShardOptions& shard = {});

/// The locks of one process on one output folder, held until destruction, which unlocks them and
/// removes their files (the folder's shared lock file only when no other shard holds it).
class OutputLock {
 public:
  OutputLock() = default;
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

  /// Lock files taken over from a holder that ended without removing them (killed, or its host
  /// went down): one warning each, naming the file and the former holder. Not for report.json:
  /// a resumed run writes what an uninterrupted one writes.
  const std::vector<std::string>& warnings() const { return warnings_; }

  /// Unlocks and removes the lock files now.
  void release();

  struct Held {
    int fd = -1;
    std::filesystem::path file;
    bool exclusive = true;
  };

 private:
  friend OutputLock lock_output_folder(const std::filesystem::path&, const ShardOptions&);
  std::vector<Held> held_;
  std::vector<std::string> warnings_;
  std::unique_ptr<OutputFolder> folder_;
};

}  // namespace sm
