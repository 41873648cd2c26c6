#include "scenarios/cache_entry.hpp"

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

}  // namespace rupture
