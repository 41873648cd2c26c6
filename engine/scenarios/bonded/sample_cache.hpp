#pragma once
// On-disk cache of packed random samples, so that runs on the same sample (a strain-rate sweep, a
// re-run, the workers of one job) skip the packing (collective rearrangement, bonds, pores), which
// takes seconds to minutes on the seed's 21,000-element sample. One HDF5 file per key:
//   <cache dir>/bonded-sample-<16 hex digits>.h5
//     attributes on "/": key, format_version, elements, bonds, checksum (FNV-1a of the datasets'
//     bytes), packing_fraction, porosity, thickness, relaxation_overlap;
//     datasets position {n,3} (m), radius {n} (m), bond {b,2} (element indices), pore {p,4} (m).
// The key is the resolved dimension + sample block + a format version and the engine version: the
// packed geometry depends on nothing else (the material is applied after loading: masses from the
// density, beams, contact). A file whose key, sizes or checksum do not match is rebuilt and
// replaced, never used. Writes go through a unique temporary file renamed into place, and an entry
// lock (CacheEntryLock, cache_entry.hpp) makes concurrent runs pack a sample once.
// Lattice samples are not cached (they build in milliseconds).
#include <atomic>
#include <string>

#include "core/cancellation.hpp"
#include "samples/sample_builder.hpp"

namespace rupture {

struct SampleCacheUse {
  bool enabled = false;     ///< the sample was eligible and a cache directory given
  bool fromCache = false;   ///< the sample was read from the cache
  std::string file;         ///< the entry read or written ("" if none)
};

/// buildSample through the cache in `directory` (no cache if empty or for lattices). `cancel` also
/// stops the wait for another run's lock. Throws RunCancelled like buildSample.
SampleReport buildSampleCached(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                               const std::string& directory, const std::atomic<bool>& cancel,
                               SampleCacheUse& use);

/// The cache file of a sample (for tests and tools).
std::string sampleCacheFile(const std::string& directory, const SampleSpec& sample);

}  // namespace rupture
