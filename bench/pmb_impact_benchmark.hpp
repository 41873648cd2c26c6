#pragma once
// Benchmark W2: PMB peridynamic block hit by a rigid sphere (see bench/README.md for the full
// definition; bench/w2_lammps.in is the same problem as a LAMMPS deck).
#include <functional>

#include <nlohmann/json.hpp>

#include "bonded/bonded_system.hpp"

namespace rupture::bench {

struct W2Options {
  int threads = 1;
  int steps = 1000;
};

/// W2's block (sample and material), set up but not initialised.
BondedSystem buildW2Block();
/// W2's rigid sphere as an external load, its centre set from the block's top face `top` (m): it
/// reads and loads each particle alone, so it serves a sub-domain of the block as it does the whole.
std::function<void(ParticleStore&, double)> w2Indenter(double top);
/// W2's time step (s).
inline constexpr double kW2TimeStep = 1e-7;

/// Builds W2, runs it and returns one JSON object: workload, particles, bonds, steps, threads,
/// seconds, particle_steps_per_s, bond_steps_per_s (+ broken_bonds, damaged_fraction, time_step).
nlohmann::json runW2(const W2Options& options);

}  // namespace rupture::bench
