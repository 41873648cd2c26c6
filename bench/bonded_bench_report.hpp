#pragma once
// The JSON line every bonded workload (W1, W2) prints: sizes, time and throughput of its run.
#include <time.h>

#include <algorithm>

#include <nlohmann/json.hpp>

#include "bonded/bonded_system.hpp"

namespace rupture::bench {

/// CPU time of the whole process, all threads (s). On a shared machine the wall clock counts the
/// time other jobs held the cores; the CPU time does not.
inline double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline nlohmann::json bondedBenchReport(const char* workload, const BondedSystem& s, int steps, int threads,
                                        double seconds, double cpuSeconds) {
  const double particleSteps = static_cast<double>(s.particles.size()) * steps;
  const double bondSteps = static_cast<double>(s.bonds.size()) * steps;
  return {{"workload", workload},
          {"particles", s.particles.size()},
          {"bonds", s.bonds.size()},
          {"steps", steps},
          {"threads", std::max(1, threads)},
          {"seconds", seconds},
          {"cpu_seconds", cpuSeconds},
          {"particle_steps_per_s", particleSteps / seconds},
          {"bond_steps_per_s", bondSteps / seconds},
          {"broken_bonds", s.bonds.size() - s.bonds.intactCount()}};
}

}  // namespace rupture::bench
