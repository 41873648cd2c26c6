#pragma once
// Wall-clock timestamps as the API and the log write them.
#include <string>

namespace rupture::server {

/// Current UTC time as RFC 3339 with milliseconds, e.g. 2026-11-21T07:43:53.123Z.
std::string utcNow();

}  // namespace rupture::server
