#include "dam_break_benchmark.hpp"
#include "checkpoint_cost.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "sph/sph_system.hpp"

namespace rupture::bench {

namespace {

// W3 constants (SI). Published in bench/README.md.
constexpr double kSpacing = 0.01;              // dx (m), simple cubic
constexpr int kColumn[3] = {50, 50, 40};       // water column 0.5 × 0.5 × 0.4 m, in cells of dx
constexpr int kTank[3] = {100, 50, 50};        // tank interior 1.0 × 0.5 × 0.5 m
constexpr int kWallLayers = 3;                 // floor and four side walls; open top
constexpr double kSupportOverSpacing = 2.6;    // 2h = 2.6 dx
constexpr double kDensity = 1000.0, kSoundSpeed = 20.0, kAlpha = 0.1, kGravity = 9.81;

void buildW3(sph::SphSystem& s) {
  sph::FluidModel& m = s.model;
  m.dimension = 3;
  m.spacing = kSpacing;
  m.smoothingRatio = 0.5 * kSupportOverSpacing;
  m.eos = {sph::EosKind::Tait, kDensity, kSoundSpeed, 7.0};
  m.alpha = kAlpha;
  m.beta = 0;
  m.diffusion = sph::DiffusionModel::Off;
  m.gravity = {0, 0, -kGravity};
  const double mass = kDensity * kSpacing * kSpacing * kSpacing;
  s.bodies.push_back({});
  s.bodies[0].name = "tank";
  // Lattice sites at (i + ½) dx; the tank interior is [0, 100) × [0, 50) × [0, 50) in sites.
  for (int k = -kWallLayers; k < kTank[2]; ++k)
    for (int j = -kWallLayers; j < kTank[1] + kWallLayers; ++j)
      for (int i = -kWallLayers; i < kTank[0] + kWallLayers; ++i) {
        const double x = (i + 0.5) * kSpacing, y = (j + 0.5) * kSpacing, z = (k + 0.5) * kSpacing;
        const bool inside = i >= 0 && i < kTank[0] && j >= 0 && j < kTank[1] && k >= 0;
        if (!inside) s.particles.add(x, y, z, mass, kDensity, 0);
        else if (i < kColumn[0] && j < kColumn[1] && k < kColumn[2]) s.particles.add(x, y, z, mass, kDensity, sph::kFluid);
      }
}

/// Directed pairs closer than the kernel support (the pairs that contribute): every interacting
/// pair is listed once, by its fluid particle of lower index (neighbour_list.hpp), and counts twice.
std::size_t pairsWithinSupport(const sph::SphSystem& s) {
  const sph::FluidParticles& p = s.particles;
  const sph::NeighbourList& list = s.neighbourList();
  const double support2 = std::pow(s.model.kernel().support(), 2);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.isFluid(i)) continue;
    const std::int32_t* nb = list.neighbours(i);
    for (int n = 0; n < list.count(i); ++n) {
      const std::int32_t j = nb[n];
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j], dz = p.z[i] - p.z[j];
      if (dx * dx + dy * dy + dz * dz < support2) pairs += 2;
    }
  }
  return pairs;
}

}  // namespace

nlohmann::json runW3(const W3Options& options) {
  omp_set_num_threads(std::max(1, options.threads));
  sph::SphSystem s;
  buildW3(s);
  s.initialise();
  const double dt = 0.1 * kSupportOverSpacing * kSpacing / kSoundSpeed;
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpuStart = std::clock();
  for (int k = 0; k < options.steps; ++k) s.step(dt);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Processor time of all threads: on a shared machine, wall time also counts other jobs' turns.
  const double cpuSeconds = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
  const double n = static_cast<double>(s.particles.size());
  const double pairs = static_cast<double>(pairsWithinSupport(s));
  const double listed = static_cast<double>(s.neighbourList().totalPairs());
  nlohmann::json report = {{"workload", "W3"},
          {"particles", s.particles.size()},
          {"fluid_particles", static_cast<std::size_t>(std::llround(s.fluidMass() / (kDensity * std::pow(kSpacing, 3))))},
          {"steps", options.steps},
          {"threads", options.threads},
          {"seconds", seconds},
          {"particle_steps_per_s", n * options.steps / seconds},
          {"pairs_per_particle", pairs / n},
          {"listed_pairs_per_particle", listed / n},
          {"ns_per_pair", 1e9 * seconds * options.threads / (pairs * options.steps)},
          {"cpu_seconds", cpuSeconds},
          {"list_builds", s.listBuilds()},
          {"time_step", dt},
          {"end_time", s.time},
          {"max_density", s.extremes().maxDensity}};
  report.update(checkpointCost([&](StateArchive& a) { s.exchangeState(a); }));
  return report;
}

}  // namespace rupture::bench
