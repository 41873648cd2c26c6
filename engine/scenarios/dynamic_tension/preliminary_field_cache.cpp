#include "scenarios/dynamic_tension/preliminary_field_cache.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <utility>

#include "io/hdf5_file.hpp"
#include "io/interleave.hpp"

namespace rupture {

namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kFormatVersion = 1;

// The scalars a cached preliminary run keeps, by attribute name: the one list that storing and
// loading both walk.
constexpr std::pair<const char*, double PreliminaryResult::*> kScalars[] = {
    {"face_velocity", &PreliminaryResult::faceVelocity},
    {"strain_rate", &PreliminaryResult::strainRate},
    {"ramp_time", &PreliminaryResult::rampTime},
    {"time_step", &PreliminaryResult::timeStep},
    {"capture_strain", &PreliminaryResult::captureStrain},
    {"capture_time", &PreliminaryResult::captureTime},
    {"onset_strain", &PreliminaryResult::onsetStrain},
    {"modulus", &PreliminaryResult::modulus},
    {"wave_speed", &PreliminaryResult::waveSpeed},
    {"equilibrium_ratio", &PreliminaryResult::equilibriumRatio},
    {"wall_time_s", &PreliminaryResult::wallTime},
};
constexpr std::pair<const char*, std::int64_t PreliminaryResult::*> kCounts[] = {
    {"capture_steps", &PreliminaryResult::captureSteps},
    {"steps", &PreliminaryResult::steps},
};

void split(const std::vector<double>& in, std::vector<double>& a, std::vector<double>& b, std::vector<double>& c) {
  const std::size_t n = in.size() / 3;
  a.resize(n); b.resize(n); c.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    a[k] = in[3 * k];
    b[k] = in[3 * k + 1];
    c[k] = in[3 * k + 2];
  }
}

}  // namespace

std::string preliminaryCacheDirectory(const std::string& configured, const std::string& resultPath) {
  if (!configured.empty()) return configured;
  if (const char* dir = std::getenv("RUPTURE_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "rupture").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "rupture").string();
  fs::path parent = fs::path(resultPath).parent_path();
  if (parent.empty()) parent = ".";
  return (parent / ".rupture-cache").string();
}

std::string preliminaryCacheFile(const std::string& directory, const nlohmann::json& key) {
  return (fs::path(directory) / ("dynamic-tension-preliminary-" + fnv1aHex(key.dump()) + ".h5")).string();
}

std::optional<PreliminaryResult> loadPreliminary(const std::string& file, const nlohmann::json& key,
                                                 std::size_t elements) {
  return readCacheEntry(file, key, kFormatVersion, [&](io::Hdf5File& f) -> std::optional<PreliminaryResult> {
    if (f.readAttributeInt("/", "elements") != static_cast<std::int64_t>(elements)) return std::nullopt;
    PreliminaryResult r;
    for (const auto& [name, member] : kScalars) r.*member = f.readAttributeDouble("/", name);
    for (const auto& [name, member] : kCounts) r.*member = f.readAttributeInt("/", name);
    const auto v = f.readDatasetDouble("/velocity");
    const auto w = f.readDatasetDouble("/angular_velocity");
    if (v.size() != 3 * elements || w.size() != 3 * elements) return std::nullopt;
    split(v, r.field.vx, r.field.vy, r.field.vz);
    split(w, r.field.wx, r.field.wy, r.field.wz);
    return r;
  });
}

bool storePreliminary(const std::string& file, const nlohmann::json& key, const PreliminaryResult& r) {
  return writeCacheEntry(file, [&](io::Hdf5File& f) {
    f.setAttribute("/", "format_version", kFormatVersion);
    f.setAttribute("/", "key", key.dump());
    f.setAttribute("/", "elements", static_cast<std::int64_t>(r.field.vx.size()));
    for (const auto& [name, member] : kScalars) f.setAttribute("/", name, r.*member);
    for (const auto& [name, member] : kCounts) f.setAttribute("/", name, r.*member);
    const std::size_t n = r.field.vx.size();
    f.writeDataset("/velocity", io::interleave(r.field.vx, r.field.vy, r.field.vz), {n, 3}, "m/s");
    f.writeDataset("/angular_velocity", io::interleave(r.field.wx, r.field.wy, r.field.wz), {n, 3}, "rad/s");
  });
}

}  // namespace rupture
