#include "common/log.hpp"

#include <cstdio>
#include <mutex>

#include "common/utc_time.hpp"

namespace rupture::server {

void logLine(const std::string& message) {
  static std::mutex mutex;
  const std::string line = utcNow() + " rupture-server: " + message + "\n";
  std::lock_guard lock(mutex);
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace rupture::server
