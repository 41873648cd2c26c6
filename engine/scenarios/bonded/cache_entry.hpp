#pragma once
// One entry of an on-disk cache (the packed samples, the VH preliminary runs): an HDF5 file whose
// root attributes "format_version" and "key" (the JSON of everything the entry depends on) are
// checked on every read, so an entry of another layout or another input is a miss, never used.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "io/hdf5_file.hpp"

namespace rupture {

/// Writes a cache entry atomically: `fill` writes a new HDF5 file under a temporary name beside
/// `file`, which is renamed to `file` once closed, so a reader never sees a partial entry. Returns
/// false (and leaves no file) when it cannot be written, e.g. in a read-only cache directory.
bool writeCacheEntry(const std::string& file, const std::function<void(io::Hdf5File&)>& fill);

/// Reads an entry written with this format version and key through `read` (which returns an
/// optional, empty for an entry that fails its own checks); empty when the file is missing, of
/// another version or key, or unreadable.
template <class Read>
auto readCacheEntry(const std::string& file, const nlohmann::json& key, std::int64_t formatVersion, Read read)
    -> decltype(read(std::declval<io::Hdf5File&>())) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  try {
    io::Hdf5File f = io::Hdf5File::openReadOnly(file);
    if (f.readAttributeInt("/", "format_version") != formatVersion) return std::nullopt;
    if (f.readAttributeString("/", "key") != key.dump()) return std::nullopt;
    return read(f);
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable, truncated or older layout: recompute
  }
}

/// An exclusive lock on one cache entry (flock on FILE.lock), so that runs starting together on the
/// same sample (a sweep's workers, or several processes) compute its preliminary run once: the
/// others wait, then read the cache. Waiting polls `cancel` every 50 ms.
class CacheEntryLock {
public:
  /// Blocks until the lock is held or `cancel` is set; held() tells which. If the lock file cannot
  /// be created (read-only cache), held() is true and nothing is locked: the run goes on uncached.
  CacheEntryLock(const std::string& file, const std::atomic<bool>& cancel);
  ~CacheEntryLock();
  CacheEntryLock(const CacheEntryLock&) = delete;
  CacheEntryLock& operator=(const CacheEntryLock&) = delete;
  bool held() const { return m_held; }

private:
  int m_fd = -1;
  bool m_held = false;
};

}  // namespace rupture
