#pragma once
// On-disk cache of VH preliminary runs, so that repeated runs on the same sample (a strain-rate
// sweep, a re-run) skip it. One small HDF5 file per key:
//   <cache dir>/dynamic-tension-preliminary-<16 hex digits>.h5
//     attributes on "/": key (the JSON the hash was taken of), format_version, elements, and every
//     scalar of PreliminaryResult; datasets velocity {n,3} (m/s), angular_velocity {n,3} (rad/s).
// The key is the resolved dimension + sample + material + the preliminary run's parameters (strain
// rate, capture rule, ramp time, time step) + a format version and the engine version (a change of
// the physics must come with a version bump, or the cache be cleared); the file name is its 64-bit
// FNV-1a hash, and the stored key is compared on load, so a collision is a miss, not a wrong field.
// Writes go to a unique temporary file in the same directory, renamed into place: concurrent runs
// (server workers) may compute the same entry, and readers only ever see complete files.
//
// Cache directory: $RUPTURE_CACHE_DIR if set; else $XDG_CACHE_HOME/rupture; else $HOME/.cache/rupture;
// else a ".rupture-cache" directory beside the result file.
#include <atomic>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/fnv1a.hpp"
#include "io/hdf5_file.hpp"
#include "scenarios/bonded/cache_entry.hpp"
#include "scenarios/dynamic_tension/preliminary_velocity_field.hpp"

namespace rupture {

/// `configured` if not empty, else $RUPTURE_CACHE_DIR, $XDG_CACHE_HOME/rupture, ~/.cache/rupture,
/// or .rupture-cache beside the result file.
std::string preliminaryCacheDirectory(const std::string& configured, const std::string& resultPath);

/// The cache file of a key (the key's compact JSON dump is hashed).
std::string preliminaryCacheFile(const std::string& directory, const nlohmann::json& key);

/// The cached result for this key and element count, or nullopt (missing, other key, unreadable).
std::optional<PreliminaryResult> loadPreliminary(const std::string& file, const nlohmann::json& key,
                                                 std::size_t elements);

/// Stores atomically; returns false (and leaves nothing behind) if the directory is not writable.
bool storePreliminary(const std::string& file, const nlohmann::json& key, const PreliminaryResult& result);

}  // namespace rupture
