#pragma once
// One-line, time-stamped log messages on stderr, safe from any thread.
#include <string>

namespace rupture::server {

void logLine(const std::string& message);

}  // namespace rupture::server
