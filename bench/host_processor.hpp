#pragma once
// The processor a benchmark ran on, printed with every benchmark's JSON line: one machine kind
// is served by hosts of different processors, and the figures differ with them (bench/README.md:
// W3 on a Zen 4 host and on a Zen 5 host).
#include <unistd.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace rupture::bench {

/// {"model_name", "family", "model"} from /proc/cpuinfo's first processor (null where absent) and
/// the L1 data cache's "l1d_bytes" and "l1d_ways" (null where the C library does not know them).
inline nlohmann::json hostProcessor() {
  nlohmann::json host = {{"model_name", nullptr}, {"family", nullptr}, {"model", nullptr}};
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line) && !line.empty()) {  // the first processor's block
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string key = line.substr(0, colon);
    key.erase(key.find_last_not_of(" \t") + 1);
    const std::string value = colon + 2 <= line.size() ? line.substr(colon + 2) : std::string();
    if (key == "model name") host["model_name"] = value;
    else if ((key == "cpu family" || key == "model") && !value.empty() &&
             value.find_first_not_of("0123456789") == std::string::npos)
      host[key == "model" ? "model" : "family"] = std::stol(value);
  }
  const long bytes = sysconf(_SC_LEVEL1_DCACHE_SIZE), ways = sysconf(_SC_LEVEL1_DCACHE_ASSOC);
  host["l1d_bytes"] = bytes > 0 ? nlohmann::json(bytes) : nlohmann::json(nullptr);
  host["l1d_ways"] = ways > 0 ? nlohmann::json(ways) : nlohmann::json(nullptr);
  return host;
}

}  // namespace rupture::bench
