#pragma once
// One server per data directory: an exclusive flock on <data-dir>/rupture.lock, held for the life
// of the server and released by the kernel when the process ends (even on SIGKILL), so a crash
// never leaves a stale lock. The file holds the owner's pid, to name it in the refusal.
#include <filesystem>

namespace rupture::server {

class DataDirLock {
public:
  /// Takes the lock; throws std::runtime_error naming the directory (and the other server's pid
  /// when the file records it) if another process holds it.
  explicit DataDirLock(const std::filesystem::path& dataDir);
  ~DataDirLock();
  DataDirLock(const DataDirLock&) = delete;
  DataDirLock& operator=(const DataDirLock&) = delete;

  static constexpr const char* kFileName = "rupture.lock";

private:
  int m_fd = -1;
};

}  // namespace rupture::server
