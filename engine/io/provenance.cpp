#include "io/provenance.hpp"

#include <sys/utsname.h>

#include <chrono>
#include <ctime>
#include <fstream>
#include <functional>

#include <omp.h>

#include "io/sha256.hpp"
#include "rupture_build_commit.hpp"  // generated at every build: RUPTURE_GIT_COMMIT
#include "rupture_build_flags.hpp"   // generated at configure: RUPTURE_COMPILER, RUPTURE_COMPILE_FLAGS, RUPTURE_BUILD_TYPE

namespace rupture::io {

namespace {
constexpr const char* kProvenanceGroup = "/provenance";
}  // namespace

const BuildInfo& buildInfo() {
  static const BuildInfo info{RUPTURE_VERSION, RUPTURE_GIT_COMMIT, RUPTURE_COMPILER, RUPTURE_COMPILE_FLAGS,
                              RUPTURE_BUILD_TYPE};
  return info;
}

std::string hostProcessor() {
  // Read once: the processor does not change under a running program, and every run file and
  // report asks for it.
  static const std::string processor = [] {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
      if (line.rfind("model name", 0) != 0) continue;
      const auto colon = line.find(':');
      if (colon == std::string::npos) break;
      const auto start = line.find_first_not_of(" \t", colon + 1);
      if (start != std::string::npos) return line.substr(start);
    }
    utsname name{};
    if (uname(&name) == 0) return std::string(name.machine);
    return std::string("unknown");
  }();
  return processor;
}

std::string utcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

nlohmann::json startProvenance(int threads) {
  const BuildInfo& b = buildInfo();
  return {{"rupture_version", b.version}, {"git_commit", b.commit},  {"compiler", b.compiler},
          {"compile_flags", b.flags},    {"build_type", b.buildType}, {"host_processor", hostProcessor()},
          {"threads", threads},          {"started_utc", utcNow()}};
}

nlohmann::json specSeeds(const nlohmann::json& resolved) {
  nlohmann::json seeds = nlohmann::json::object();
  const std::function<void(const nlohmann::json&, const std::string&)> visit = [&](const nlohmann::json& node,
                                                                                   const std::string& path) {
    if (!node.is_object()) return;
    for (const auto& [key, value] : node.items()) {
      const std::string here = path.empty() ? key : path + "." + key;
      const bool named = key == "seed" || (key.size() > 5 && key.ends_with("_seed"));
      if (named && value.is_number_integer()) seeds[here] = value;
      else visit(value, here);
    }
  };
  visit(resolved, "");
  return seeds;
}

void writeStartProvenance(Hdf5File& file) {
  file.createGroup(kProvenanceGroup);
  const nlohmann::json start = startProvenance(omp_get_max_threads());  // held: items() does not hold it
  for (const auto& [name, value] : start.items()) {
    if (value.is_number_integer()) file.setAttribute(kProvenanceGroup, name, value.get<std::int64_t>());
    else file.setAttribute(kProvenanceGroup, name, value.get<std::string>());
  }
}

void writeSpecProvenance(Hdf5File& file, const nlohmann::json& resolved) {
  if (!file.exists(kProvenanceGroup)) file.createGroup(kProvenanceGroup);
  file.setAttribute(kProvenanceGroup, "spec_sha256", sha256Hex(resolved.dump()));
  file.setAttribute(kProvenanceGroup, "seeds", specSeeds(resolved).dump());
}

void writeFinishProvenance(Hdf5File& file) {
  if (!file.exists(kProvenanceGroup)) file.createGroup(kProvenanceGroup);
  file.setAttribute(kProvenanceGroup, "finished_utc", utcNow());
}

}  // namespace rupture::io
