#include "scenarios/bonded/sample_cache.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <system_error>

#include "bonded/bonded_spec.hpp"
#include "core/fnv1a.hpp"
#include "io/hdf5_file.hpp"
#include "io/interleave.hpp"
#include "scenarios/bonded/cache_entry.hpp"

namespace rupture {

namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kFormatVersion = 2;  // 2: elements in spatial order (samples/spatial_order.hpp)

nlohmann::json cacheKey(const SampleSpec& sample) {
  return {{"format", kFormatVersion},
          {"engine", RUPTURE_VERSION},
          {"dimension", sample.dimension},
          {"sample", io::toJson(sample)}};
}

/// FNV-1a over the bytes of the stored arrays, so that a damaged entry is detected, not used.
template <class... Vectors>
std::string checksum(const Vectors&... v) {
  std::string bytes;
  (bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0])), ...);
  return fnv1aHex(bytes);
}

struct PackedSample {
  std::vector<double> position, radius, pore;
  std::vector<std::int32_t> bond;
  SampleReport report;
};

PackedSample capture(const BondedSystem& system, const SampleReport& report) {
  const ParticleStore& p = system.particles;
  PackedSample s;
  s.position = io::interleave(p.x, p.y, p.z);
  s.radius = p.radius;
  s.bond.reserve(2 * system.bonds.size());
  for (std::size_t b = 0; b < system.bonds.size(); ++b) {
    s.bond.push_back(system.bonds.i[b]);
    s.bond.push_back(system.bonds.j[b]);
  }
  for (const Pore& pore : report.pores)
    s.pore.insert(s.pore.end(), {pore.centre[0], pore.centre[1], pore.centre[2], pore.radius});
  s.report = report;
  return s;
}

std::optional<PackedSample> load(const std::string& file, const nlohmann::json& key) {
  return readCacheEntry(file, key, kFormatVersion, [&](io::Hdf5File& f) -> std::optional<PackedSample> {
    PackedSample s;
    s.position = f.readDatasetDouble("/position");
    s.radius = f.readDatasetDouble("/radius");
    s.pore = f.readDatasetDouble("/pore");
    const std::vector<std::int64_t> bonds = f.readDatasetInt("/bond");
    const auto n = static_cast<std::size_t>(f.readAttributeInt("/", "elements"));
    const auto b = static_cast<std::size_t>(f.readAttributeInt("/", "bonds"));
    if (s.position.size() != 3 * n || s.radius.size() != n || bonds.size() != 2 * b || s.pore.size() % 4 != 0)
      return std::nullopt;
    for (std::int64_t k : bonds) {
      if (k < 0 || static_cast<std::size_t>(k) >= n) return std::nullopt;
      s.bond.push_back(static_cast<std::int32_t>(k));
    }
    if (f.readAttributeString("/", "checksum") != checksum(s.position, s.radius, s.bond, s.pore)) return std::nullopt;
    SampleReport& r = s.report;
    r.packingFraction = f.readAttributeDouble("/", "packing_fraction");
    r.porosity = f.readAttributeDouble("/", "porosity");
    r.thickness = f.readAttributeDouble("/", "thickness");
    r.relaxationOverlap = f.readAttributeDouble("/", "relaxation_overlap");
    if (!(r.packingFraction > 0)) return std::nullopt;
    for (std::size_t k = 0; k < s.pore.size(); k += 4)
      r.pores.push_back({{s.pore[k], s.pore[k + 1], s.pore[k + 2]}, s.pore[k + 3]});
    return s;
  });
}

void store(const std::string& file, const nlohmann::json& key, const PackedSample& s) {
  // A read-only cache: the run goes on without it (writeCacheEntry leaves no file).
  writeCacheEntry(file, [&](io::Hdf5File& f) {
    const std::size_t n = s.radius.size(), b = s.bond.size() / 2;
    f.setAttribute("/", "format_version", kFormatVersion);
    f.setAttribute("/", "key", key.dump());
    f.setAttribute("/", "elements", static_cast<std::int64_t>(n));
    f.setAttribute("/", "bonds", static_cast<std::int64_t>(b));
    f.setAttribute("/", "checksum", checksum(s.position, s.radius, s.bond, s.pore));
    f.setAttribute("/", "packing_fraction", s.report.packingFraction);
    f.setAttribute("/", "porosity", s.report.porosity);
    f.setAttribute("/", "thickness", s.report.thickness);
    f.setAttribute("/", "relaxation_overlap", s.report.relaxationOverlap);
    f.writeDataset("/position", s.position, {n, 3}, "m");
    f.writeDataset("/radius", s.radius, {n}, "m");
    f.writeDataset("/bond", s.bond, {b, 2}, "1");
    f.writeDataset("/pore", s.pore, {s.pore.size() / 4, 4}, "m");
  });
}

/// The packed system from a cache entry: the same elements, bonds (rest state from the same
/// positions) and masses as packRandomSample gives.
void restore(const PackedSample& s, const SampleSpec& spec, const MaterialSpec& material, BondedSystem& system,
             SampleReport& report) {
  system = BondedSystem{};
  ParticleStore& p = system.particles;
  p.dimension = spec.dimension;
  for (std::size_t k = 0; k < s.radius.size(); ++k)
    p.add(s.position[3 * k], s.position[3 * k + 1], s.position[3 * k + 2], s.radius[k]);
  report = s.report;
  report.elementDensity = material.density / report.packingFraction;  // ρ V_box / Σ V_i of the dense packing
  p.setMassFromDensity(report.elementDensity, report.thickness);
  for (std::size_t k = 0; k < s.bond.size(); k += 2) system.bonds.add(p, s.bond[k], s.bond[k + 1]);
}

}  // namespace

std::string sampleCacheFile(const std::string& directory, const SampleSpec& sample) {
  return (fs::path(directory) / ("bonded-sample-" + fnv1aHex(cacheKey(sample).dump()) + ".h5")).string();
}

SampleReport buildSampleCached(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                               const std::string& directory, const std::atomic<bool>& cancel, SampleCacheUse& use) {
  use = {};
  if (directory.empty() || sample.lattice != "random") return buildSample(sample, material, system, &cancel);
  use.enabled = true;
  use.file = sampleCacheFile(directory, sample);
  const nlohmann::json key = cacheKey(sample);
  const CacheEntryLock lock(use.file, cancel);  // held until the entry is read or written
  if (!lock.held()) throw RunCancelled();
  SampleReport report;
  if (const std::optional<PackedSample> cached = load(use.file, key)) {
    restore(*cached, sample, material, system, report);
    use.fromCache = true;
  } else {
    report = packRandomSample(sample, material, system, &cancel);
    store(use.file, key, capture(system, report));
  }
  finishRandomSample(sample, material, system, report, &cancel);
  return report;
}

}  // namespace rupture
