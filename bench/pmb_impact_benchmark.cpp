#include "pmb_impact_benchmark.hpp"
#include "checkpoint_cost.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bonded_bench_report.hpp"
#include "samples/sample_builder.hpp"

namespace rupture::bench {

namespace {

// W2 constants (SI). Published in bench/README.md; the same as the LAMMPS deck w2.in.
constexpr double kSpacing = 0.5e-3;          // dx (m)
constexpr int kSites[3] = {50, 50, 40};      // 100,000 particles
constexpr double kBulkModulus = 14.9e9;      // K (Pa); E = 3K(1 − 2ν) with ν = 1/4
constexpr double kDensity = 2200;            // kg/m³
constexpr double kHorizonFactor = 3.015;     // δ / dx
constexpr double kCriticalStretch = 0.0005;  // s00
constexpr double kAlpha = 0.25;              // compression term
constexpr double kIndenterRadius = 5 * kSpacing;
constexpr double kIndenterSpeed = 100.0;     // m/s, towards −z
constexpr double kIndenterStiffness = 1e17;  // N/m² (LAMMPS fix indent: F = K (R − r)²)

}  // namespace

BondedSystem buildW2Block() {
  SampleSpec sample;
  sample.dimension = 3;
  sample.lattice = "simple-cubic";
  sample.spacing = kSpacing;
  sample.elementRadius = 0.5 * kSpacing;
  for (int a = 0; a < 3; ++a) sample.size[a] = kSites[a] * kSpacing;
  MaterialSpec material;
  material.model = "pmb";
  material.density = kDensity;
  material.pmb.youngModulus = 1.5 * kBulkModulus;
  material.pmb.horizonFactor = kHorizonFactor;
  material.pmb.criticalStretch = kCriticalStretch;
  material.pmb.compressionFactor = kAlpha;
  material.pmb.partialVolume = "linear";  // LAMMPS's bonds and volume scaling
  material.contact.youngModulus = material.pmb.youngModulus;
  material.contact.poissonRatio = 0.25;
  material.contact.enabled = false;  // the bond kernel and the indenter only (see bench/README.md)
  BondedSystem s;
  buildSample(sample, material, s);
  return s;
}

std::function<void(ParticleStore&, double)> w2Indenter(double top) {
  // The rigid sphere: centred above the middle of the top face, 0.1 dx above it at t = 0.
  const double cx = 0.5 * kSites[0] * kSpacing, cy = 0.5 * kSites[1] * kSpacing;
  const double z0 = top + kIndenterRadius + 0.1 * kSpacing;
  return [=](ParticleStore& ps, double t) {
    const double cz = z0 - kIndenterSpeed * t;
    const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(ps.size());
    // Only sites near the sphere can be touched: a cheap band test first.
#pragma omp parallel for schedule(static) if (n > 8192)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      const double ez = ps.z[k] - cz;
      if (ez > kIndenterRadius || ez < -kIndenterRadius) continue;
      const double ex = ps.x[k] - cx, ey = ps.y[k] - cy;
      const double r2 = ex * ex + ey * ey + ez * ez;
      if (r2 >= kIndenterRadius * kIndenterRadius) continue;
      const double r = std::sqrt(r2), overlap = kIndenterRadius - r;
      const double f = kIndenterStiffness * overlap * overlap / r;
      ps.fx[k] += f * ex; ps.fy[k] += f * ey; ps.fz[k] += f * ez;
    }
  };
}

nlohmann::json runW2(const W2Options& options) {
  omp_set_num_threads(std::max(1, options.threads));
  BondedSystem s = buildW2Block();
  ParticleStore& p = s.particles;
  s.externalLoads = w2Indenter(*std::max_element(p.z.begin(), p.z.end()));
  s.initialize();

  const double cpuStart = processCpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  for (int step = 0; step < options.steps; ++step) s.step(kW2TimeStep);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpuSeconds = processCpuSeconds() - cpuStart;

  double meanDamage = 0;  // the system keeps φ up to date as bonds break
  for (double d : s.damageIndex()) meanDamage += d;
  meanDamage /= static_cast<double>(p.size());
  nlohmann::json report = bondedBenchReport("W2", s, options.steps, options.threads, seconds, cpuSeconds);
  report["mean_damage"] = meanDamage;
  report["time_step"] = kW2TimeStep;
  report["stable_time_step"] = s.criticalTimeStep();
  report.update(checkpointCost([&](StateArchive& a) { s.exchangeState(a); }));
  return report;
}

}  // namespace rupture::bench
