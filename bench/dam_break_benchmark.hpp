#pragma once
// Benchmark W3: 3D weakly compressible SPH dam break in a walled tank (see bench/README.md for the
// full definition, so that other codes can run the same problem).
#include <nlohmann/json.hpp>

namespace rupture::bench {

struct W3Options {
  int threads = 1;
  int steps = 1000;
};

/// Builds W3, runs it and returns one JSON object: workload, particles, steps, threads, seconds,
/// particle_steps_per_s, pairs_per_particle (+ ns_per_pair, list_builds, time_step).
nlohmann::json runW3(const W3Options& options);

}  // namespace rupture::bench
