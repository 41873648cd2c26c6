#pragma once
// Benchmark W1: bonded fcc bar in tension (see bench/README.md for the full definition, so that
// other codes can run the same problem).
#include <cstddef>

#include <nlohmann/json.hpp>

#include "bonded/bonded_system.hpp"

namespace rupture::bench {

struct W1Options {
  int threads = 1;
  std::size_t particles = 102400;  ///< scales the 64 × 20 × 20 fcc cell box
  int steps = 1000;
  /// Weibull modulus m of a per-bond stiffness factor of mean 1 (material.disorder's stiffness);
  /// 0 = off, every factor 1 (the workload as defined). Times the loop with the option on.
  double stiffnessWeibullModulus = 0;
};

/// W1's bar of about `particles` spheres (the 64 × 20 × 20 cell box scaled in all three
/// directions) into `s`: sample, beams, contact, jitter, slabs and velocities; not initialised.
void buildW1Bar(BondedSystem& s, std::size_t particles, double stiffnessWeibullModulus = 0);
/// W1's time step (s): 0.15 of the beams' critical step of the initialised bar.
double w1TimeStep(const BondedSystem& initialisedBar);

/// Builds W1, runs it and returns one JSON object: workload, particles, bonds, steps, threads,
/// seconds, particle_steps_per_s, bond_steps_per_s (+ broken_bonds, time_step).
nlohmann::json runW1(const W1Options& options);

}  // namespace rupture::bench
