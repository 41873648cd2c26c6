#pragma once
// The JSON line every bonded workload (W1, W2) prints: sizes, time and throughput of its run.
#include <algorithm>

#include <nlohmann/json.hpp>

#include "dem/bonded_system.hpp"

namespace rupture::bench {

inline nlohmann::json bondedBenchReport(const char* workload, const BondedSystem& s, int steps, int threads,
                                        double seconds) {
  const double particleSteps = static_cast<double>(s.particles.size()) * steps;
  const double bondSteps = static_cast<double>(s.bonds.size()) * steps;
  return {{"workload", workload},
          {"particles", s.particles.size()},
          {"bonds", s.bonds.size()},
          {"steps", steps},
          {"threads", std::max(1, threads)},
          {"seconds", seconds},
          {"particle_steps_per_s", particleSteps / seconds},
          {"bond_steps_per_s", bondSteps / seconds},
          {"broken_bonds", s.bonds.size() - s.bonds.intactCount()}};
}

}  // namespace rupture::bench
