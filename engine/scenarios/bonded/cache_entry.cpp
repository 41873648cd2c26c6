#include "scenarios/bonded/cache_entry.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>

namespace rupture {
namespace fs = std::filesystem;

bool writeCacheEntry(const std::string& file, const std::function<void(io::Hdf5File&)>& fill) {
  static std::atomic<unsigned> counter{0};
  const fs::path target(file);
  const fs::path tmp = target.parent_path() / (target.filename().string() + ".tmp." + std::to_string(::getpid()) +
                                               "." + std::to_string(counter++));
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  try {
    {
      io::Hdf5File f = io::Hdf5File::create(tmp.string());
      fill(f);
      f.close();
    }
    fs::rename(tmp, target);
    return true;
  } catch (const std::exception&) {
    fs::remove(tmp, ec);
    return false;
  }
}

CacheEntryLock::CacheEntryLock(const std::string& file, const std::atomic<bool>& cancel) {
  std::error_code ec;
  fs::create_directories(fs::path(file).parent_path(), ec);
  m_fd = ::open((file + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (m_fd < 0) {
    m_held = true;  // nothing to lock with: behave as the only run
    return;
  }
  while (!(m_held = ::flock(m_fd, LOCK_EX | LOCK_NB) == 0)) {
    if (cancel.load(std::memory_order_relaxed)) return;
    ::usleep(50000);
  }
}

CacheEntryLock::~CacheEntryLock() {
  if (m_fd >= 0) ::close(m_fd);  // closing the descriptor releases the lock
}

}  // namespace rupture
