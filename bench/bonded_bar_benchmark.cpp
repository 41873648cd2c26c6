#include "bonded_bar_benchmark.hpp"
#include "checkpoint_cost.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "bonded_bench_report.hpp"
#include "bonded/bonded_system.hpp"
#include "samples/bond_disorder.hpp"

namespace rupture::bench {

namespace {

// W1 constants (SI). Published in bench/README.md.
constexpr double kDiameter = 1e-3;          // d (m)
constexpr double kDensity = 2500.0;         // kg/m³
constexpr double kYoungModulus = 70e9;      // E_μ (Pa)
constexpr double kPoissonRatio = 0.25;      // ν_μ
constexpr double kRadiusRatio = 0.5;        // r_μ / R
constexpr double kFailureStress = 6.5e9;    // σ_f (Pa): the jitter loads a few beams near it    // σ_f (Pa)
constexpr double kJitter = 0.02;            // × d, uniform per component, after bonding
constexpr double kPullVelocity = 2.0;       // m/s, the moving slab
constexpr double kSafety = 0.15;            // dt = 0.15 dt_c

void buildFcc(BondedSystem& s, int nx, int ny, int nz) {
  const double a = kDiameter * std::sqrt(2.0);  // cubic cell edge: nearest neighbours at d
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  ParticleStore& p = s.particles;
  p.dimension = 3;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        for (const auto& b : basis)
          p.add((i + b[0]) * a, (j + b[1]) * a, (k + b[2]) * a, 0.5 * kDiameter);
  p.setMassFromDensity(kDensity, 0.0);
}

}  // namespace

void buildW1Bar(BondedSystem& s, std::size_t particles, double stiffnessWeibullModulus) {
  const double scale = std::cbrt(static_cast<double>(particles) / 102400.0);
  const int nx = std::max(2, static_cast<int>(std::lround(64 * scale)));
  const int ny = std::max(2, static_cast<int>(std::lround(20 * scale)));
  const int nz = ny;

  s.beam = {kYoungModulus, kPoissonRatio, kRadiusRatio, kFailureStress};
  s.contact.setParameters({kYoungModulus, kPoissonRatio, 0.3, 0.1, true});
  buildFcc(s, nx, ny, nz);
  ParticleStore& p = s.particles;
  // Bonds: every pair closer than 1.1 d (12 per interior sphere), found with a cell list.
  CellList cells;
  cells.build(p, 1.1 * kDiameter);
  for (std::size_t a = 0; a < p.size(); ++a)
    cells.forEachNear(p.x[a], p.y[a], p.z[a], [&](std::int32_t b) {
      if (static_cast<std::size_t>(b) <= a) return;
      const double dx = p.x[b] - p.x[a], dy = p.y[b] - p.y[a], dz = p.z[b] - p.z[a];
      if (dx * dx + dy * dy + dz * dz < 1.21 * kDiameter * kDiameter) s.bonds.add(p, a, b);
    });

  // Jitter after bonding: the bonds start slightly loaded, as in a real packing.
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> jitter(-kJitter * kDiameter, kJitter * kDiameter);
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.x[k] += jitter(rng); p.y[k] += jitter(rng); p.z[k] += jitter(rng);
  }

  // Slabs of 1.5 d at each end in x; interior on the matching linear velocity ramp.
  const auto [minIt, maxIt] = std::minmax_element(p.x.begin(), p.x.end());
  const double xMin = *minIt, xMax = *maxIt;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.x[k] < xMin + 1.5 * kDiameter) {
      p.fixedDofs[k] = kFixX | kFixY | kFixZ;
    } else if (p.x[k] > xMax - 1.5 * kDiameter) {
      p.fixedDofs[k] = kFixX | kFixY | kFixZ;
      p.vx[k] = kPullVelocity;
    } else {
      p.vx[k] = kPullVelocity * (p.x[k] - xMin) / (xMax - xMin);
    }
  }
  if (stiffnessWeibullModulus > 0) {
    BondDisorder disorder;
    disorder.stiffness.kind = FactorDistribution::Kind::Weibull;
    disorder.stiffness.weibullModulus = stiffnessWeibullModulus;
    disorder.seed = 20261121;
    applyBondDisorder(disorder, s.bonds);
  }
}

double w1TimeStep(const BondedSystem& initialisedBar) { return kSafety * initialisedBar.criticalTimeStep(); }

nlohmann::json runW1(const W1Options& options) {
  omp_set_num_threads(std::max(1, options.threads));
  BondedSystem s;
  buildW1Bar(s, options.particles, options.stiffnessWeibullModulus);
  s.initialize();
  const double initialPeakStress =
      *std::max_element(s.bonds.failureMeasure.begin(), s.bonds.failureMeasure.end());
  const double dt = w1TimeStep(s);

  const double cpuStart = processCpuSeconds();
  const auto start = std::chrono::steady_clock::now();
  for (int step = 0; step < options.steps; ++step) s.step(dt);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpuSeconds = processCpuSeconds() - cpuStart;

  nlohmann::json report = bondedBenchReport("W1", s, options.steps, options.threads, seconds, cpuSeconds);
  report["time_step"] = dt;
  report["stiffness_weibull_modulus"] = options.stiffnessWeibullModulus;
  report["initial_peak_equivalent_stress"] = initialPeakStress;
  report.update(checkpointCost([&](StateArchive& a) { s.exchangeState(a); }));
  return report;
}

}  // namespace rupture::bench
