#pragma once
// Benchmark W2: PMB peridynamic block hit by a rigid sphere (see bench/README.md for the full
// definition; bench/w2_lammps.in is the same problem as a LAMMPS deck).
#include <nlohmann/json.hpp>

namespace rupture::bench {

struct W2Options {
  int threads = 1;
  int steps = 1000;
};

/// Builds W2, runs it and returns one JSON object: workload, particles, bonds, steps, threads,
/// seconds, particle_steps_per_s, bond_steps_per_s (+ broken_bonds, damaged_fraction, time_step).
nlohmann::json runW2(const W2Options& options);

}  // namespace rupture::bench
