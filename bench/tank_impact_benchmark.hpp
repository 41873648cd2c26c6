#pragma once
// Benchmark TANK: the tank-impact scenario on the coarse FXA5 example (examples/tank-impact-FXA5-coarse.json, the
// seed's test 15: 2 mm plate with an X pre-crack, 245 kg at 5 m/s), run for a given number of fluid
// steps; the fluid's particle-steps per second and the shell's node-steps per second are reported
// separately (bench/README.md).
#include <string>

#include <nlohmann/json.hpp>

namespace rupture::bench {

struct TankImpactOptions {
  int threads = 1;
  int steps = 200;   ///< fluid steps (the shell makes its sub-cycles inside them)
  std::string spec;  ///< the spec file (default: the coarse FXA5 example of the source tree)
};

/// Runs it and returns one JSON object: workload, fluid and plate counts, steps, shell steps,
/// seconds of fluid, shell and contact, fluid_particle_steps_per_s, shell_node_steps_per_s.
nlohmann::json runTankImpactBenchmark(const TankImpactOptions& options);

/// TANK-SEED: the seed's TF14A5 at the seed's inputs (examples/tank-impact-TF14A5.json: the fluid at
/// 2 mm and the plate's band at the step at 0.5 mm, Caleyron et al. 2013 §4.2, §5.3.1),
/// run whole to `endTime` (the seed's window: 2.5 ms), the shell single-rate or subcycled.
struct TankSeedOptions {
  int threads = 1;
  double endTime = 2.5e-3;  ///< s
  int subcycling = -1;      ///< 1 on, 0 off, -1 the spec's default
  std::string stepEstimate;  ///< "bound" or "spectral"; empty: the spec's default
};

/// Runs it and returns one JSON object: the wall time and its split, the fluid's particle-steps
/// and the shell's node-updates per second, the shell's fine steps per fluid step and its points
/// per class, and the physics the seed is compared on (time and place of the first fracture, the
/// first pressure peak).
nlohmann::json runTankSeedBenchmark(const TankSeedOptions& options);

}  // namespace rupture::bench
