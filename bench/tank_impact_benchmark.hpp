#pragma once
// Benchmark TANK: the tank-impact scenario on the FXA5 example (examples/tank-impact-FXA5.json, the
// seed's test 15: 2 mm plate with an X pre-crack, 245 kg at 5 m/s), run for a given number of fluid
// steps; the fluid's particle-steps per second and the shell's node-steps per second are reported
// separately (bench/README.md).
#include <string>

#include <nlohmann/json.hpp>

namespace rupture::bench {

struct TankImpactOptions {
  int threads = 1;
  int steps = 200;   ///< fluid steps (the shell makes its sub-cycles inside them)
  std::string spec;  ///< the spec file (default: the FXA5 example of the source tree)
};

/// Runs it and returns one JSON object: workload, fluid and plate counts, steps, shell steps,
/// seconds of fluid, shell and contact, fluid_particle_steps_per_s, shell_node_steps_per_s.
nlohmann::json runTankImpactBenchmark(const TankImpactOptions& options);

}  // namespace rupture::bench
