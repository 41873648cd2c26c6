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

#include "io/hdf5_file.hpp"
#include "io/interleave.hpp"

namespace rupture {

namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kFormatVersion = 1;

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
    auto d = [&](const char* name) { return f.readAttributeDouble("/", name); };
    auto i = [&](const char* name) { return f.readAttributeInt("/", name); };
    r.faceVelocity = d("face_velocity");
    r.strainRate = d("strain_rate");
    r.rampTime = d("ramp_time");
    r.timeStep = d("time_step");
    r.captureStrain = d("capture_strain");
    r.captureTime = d("capture_time");
    r.captureSteps = i("capture_steps");
    r.steps = i("steps");
    r.onsetStrain = d("onset_strain");
    r.modulus = d("modulus");
    r.waveSpeed = d("wave_speed");
    r.equilibriumRatio = d("equilibrium_ratio");
    r.wallTime = d("wall_time_s");
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
    f.setAttribute("/", "face_velocity", r.faceVelocity);
    f.setAttribute("/", "strain_rate", r.strainRate);
    f.setAttribute("/", "ramp_time", r.rampTime);
    f.setAttribute("/", "time_step", r.timeStep);
    f.setAttribute("/", "capture_strain", r.captureStrain);
    f.setAttribute("/", "capture_time", r.captureTime);
    f.setAttribute("/", "capture_steps", r.captureSteps);
    f.setAttribute("/", "steps", r.steps);
    f.setAttribute("/", "onset_strain", r.onsetStrain);
    f.setAttribute("/", "modulus", r.modulus);
    f.setAttribute("/", "wave_speed", r.waveSpeed);
    f.setAttribute("/", "equilibrium_ratio", r.equilibriumRatio);
    f.setAttribute("/", "wall_time_s", r.wallTime);
    const std::size_t n = r.field.vx.size();
    f.writeDataset("/velocity", io::interleave(r.field.vx, r.field.vy, r.field.vz), {n, 3}, "m/s");
    f.writeDataset("/angular_velocity", io::interleave(r.field.wx, r.field.wy, r.field.wz), {n, 3}, "rad/s");
  });
}

}  // namespace rupture
