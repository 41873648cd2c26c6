// S1 — SPH shell plate: particle-steps per second of the clamped circular AU4G plate (Ø 80 mm,
// 2 mm thick, elastic–plastic with Lemaitre–Chaboche damage, 5 layers) under a 1 MPa pressure
// step. One JSON line on stdout. Options: --spacing m (default 1e-3: about 5,000 nodes),
// --steps N (default 1000), --threads N.
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "shell/sph_shell.hpp"
#include "shell_state_hash.hpp"

int main(int argc, char** argv) {
  double spacing = 1.0e-3;
  int steps = 1000;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--spacing") spacing = std::atof(argv[i + 1]);
    else if (key == "--steps") steps = std::atoi(argv[i + 1]);
    else if (key == "--threads") omp_set_num_threads(std::atoi(argv[i + 1]));
    else { std::fprintf(stderr, "unknown option %s\n", argv[i]); return 2; }
  }
  if (!(spacing > 0.0 && spacing <= 0.02) || steps < 1) {
    std::fprintf(stderr, "--spacing must be in (0, 0.02] m and --steps >= 1\n");
    return 2;
  }
  rupture::ShellParameters params;
  params.thickness = 2.0e-3;
  params.damage = true;
  const rupture::ShellNodes nodes = rupture::clampedDiskNodes(0.04, spacing, 0);
  rupture::SphShell shell(nodes, params);
  shell.setPressure(1.0e6);
  const double dt = shell.stableTimeStep();
  const auto start = std::chrono::steady_clock::now();
  shell.advance(steps, dt, {});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& t = shell.timings();
  std::printf("{\"workload\": \"S1\", \"nodes\": %zu, \"steps\": %d, \"threads\": %d, \"seconds\": %.4f, "
              "\"particle_steps_per_s\": %.4g, \"time_step\": %.4g, \"centre_deflection\": %.17g, "
              "\"gradients_s\": %.3f, \"layers_s\": %.3f, \"forces_s\": %.3f, \"integration_s\": %.3f, \"state_hash\": %llu}\n",
              shell.size(), steps, omp_get_max_threads(), seconds, shell.size() * double(steps) / seconds, dt,
              shell.deflection(0), t.gradients, t.layers, t.forces, t.integration,
              static_cast<unsigned long long>(rupture::bench::shellStateHash(shell)));
  return 0;
}
