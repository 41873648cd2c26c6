// The optimised pair loop (half neighbour lists, per-chunk sums, folded kernel constants) against
// a direct evaluation of the documented equations over every pair of particles
// (engine/sph/README.md, fluid_rates.hpp): each pair within the support must be counted once for
// each of its particles, fluid–wall pairs included, diffusion only between fluid particles.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "sph/fluid_rates.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/simd_lanes.hpp"

namespace rupture::sph {
namespace {

FluidModel testModel() {
  FluidModel m;
  m.dimension = 3;
  m.spacing = 0.01;
  m.smoothingRatio = 1.3;
  m.eos = {EosKind::Tait, 1000.0, 20.0, 7.0};
  m.alpha = 0.1;
  m.beta = 0.05;
  m.diffusion = DiffusionModel::Fourtakas;
  m.delta = 0.1;
  m.gravity = {0, 0, -9.81};
  return m;
}

/// A jittered fluid block (28 × 28 × 20 sites) over a three-layer floor of boundary particles:
/// 18,032 particles, enough for the loop to split into several chunks. Random velocities and
/// densities so that every term (pressure, viscosity on approaching pairs, diffusion) is active.
FluidParticles jitteredBlock(bool equalMasses, std::uint64_t seed) {
  const double dx = 0.01;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2 * dx, 0.2 * dx), speed(-0.5, 0.5), density(990.0, 1010.0),
      massFactor(0.9, 1.1);
  FluidParticles p;
  for (int k = -3; k < 20; ++k)
    for (int j = 0; j < 28; ++j)
      for (int i = 0; i < 28; ++i) {
        const bool fluid = k >= 0;
        const double m = 1.0 * (equalMasses ? 1.0 : massFactor(rng));
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx, z = (k + 0.5) * dx;
        if (fluid) p.add(x + jitter(rng), y + jitter(rng), z + jitter(rng), m, density(rng), kFluid);
        else p.add(x, y, z, m, 1000.0, 0);
      }
  p.vxEst = p.vx;
  p.vyEst = p.vy;
  p.vzEst = p.vz;
  for (std::size_t a = 0; a < p.size(); ++a)
    if (p.isFluid(a)) {
      p.vxEst[a] = speed(rng);
      p.vyEst[a] = speed(rng);
      p.vzEst[a] = speed(rng);
    }
  p.rhoEst = p.rho;
  return p;
}

struct Reference {
  std::vector<double> ax, ay, az, drho;
  std::vector<double> pressure, rho;  // the boundary particles' extrapolated ones among them
  double maxMu = 0;
};

/// The equations of fluid_rates.hpp summed over all pairs closer than 2h, O(n²).
Reference directSums(const FluidParticles& p, const FluidModel& model) {
  const std::size_t n = p.size();
  const CubicSplineKernel kernel = model.kernel();
  const EquationOfState& eos = model.eos;
  const double h = kernel.h(), support2 = kernel.support() * kernel.support(), c0 = eos.soundSpeed;
  const auto& g = model.gravity;
  std::vector<double> pressure(n), rho(p.rhoEst.begin(), p.rhoEst.end());
  for (std::size_t a = 0; a < n; ++a)
    if (p.isFluid(a)) pressure[a] = eos.pressure(rho[a]);
  for (std::size_t w = 0; w < n; ++w) {  // Adami et al. (2012) eq. 27
    if (p.isFluid(w)) continue;
    double sumW = 0, sum = 0;
    for (std::size_t f = 0; f < n; ++f) {
      if (!p.isFluid(f)) continue;
      const double dx = p.x[w] - p.x[f], dy = p.y[w] - p.y[f], dz = p.z[w] - p.z[f];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= support2) continue;
      const double W = kernel.value(std::sqrt(r2));
      sumW += W;
      sum += (pressure[f] + rho[f] * (g[0] * dx + g[1] * dy + g[2] * dz)) * W;
    }
    pressure[w] = sumW > 0 ? std::max(0.0, sum / sumW) : 0.0;
    rho[w] = pressure[w] > 0 ? eos.density(pressure[w]) : eos.referenceDensity;
  }
  Reference ref;
  ref.pressure = pressure;
  ref.rho = rho;
  ref.ax.assign(n, 0);
  ref.ay.assign(n, 0);
  ref.az.assign(n, 0);
  ref.drho.assign(n, 0);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      if (a == b || (!p.isFluid(a) && !p.isFluid(b))) continue;
      const double dx = p.x[a] - p.x[b], dy = p.y[a] - p.y[b], dz = p.z[a] - p.z[b];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= support2) continue;
      const double F = kernel.gradientFactor(std::sqrt(r2));
      const double vr = (p.vxEst[a] - p.vxEst[b]) * dx + (p.vyEst[a] - p.vyEst[b]) * dy + (p.vzEst[a] - p.vzEst[b]) * dz;
      const double mu = h * vr / (r2 + 0.01 * h * h);
      ref.maxMu = std::max(ref.maxMu, std::fabs(mu));
      const double viscous = vr < 0 ? (-model.alpha * c0 * mu + model.beta * mu * mu) * 0.5 * (1 / rho[a] + 1 / rho[b]) : 0.0;
      const double c = p.mass[b] * (pressure[a] / (rho[a] * rho[a]) + pressure[b] / (rho[b] * rho[b]) + viscous) * F;
      ref.ax[a] -= c * dx;
      ref.ay[a] -= c * dy;
      ref.az[a] -= c * dz;
      if (!p.isFluid(a)) continue;  // boundary densities are extrapolated, not integrated
      ref.drho[a] += p.mass[b] * F * vr;
      if (p.isFluid(b)) {
        const double hydrostatic = eos.referenceDensity * (g[0] * dx + g[1] * dy + g[2] * dz) / (c0 * c0);
        ref.drho[a] += 2 * model.delta * h * c0 * ((rho[a] - rho[b]) - hydrostatic) * F * p.mass[b] / rho[b];
      }
    }
  return ref;
}

double maxAbs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

TEST(SphPairLoop, HalfListsAndChunkSumsMatchTheDirectSumOverAllPairs) {
  const FluidModel model = testModel();
  // The portable loop and both vector widths (simd_lanes.hpp): Lanes4 and Lanes8 with AVX-512, the
  // AVX2 lanes for both without it, the portable loop again where the build has neither.
  for (int laneWidth : {kPortableLanes, 4, 8})
  for (bool equalMasses : {true, false}) {
    FluidParticles p = jitteredBlock(equalMasses, equalMasses ? 11 : 12);
    NeighbourList list;
    list.build(p, 3, 1.1 * model.kernel().support());
    ASSERT_GE(list.chunks().size(), 4u) << "the block must exercise several chunks";
    RateWorkspace workspace;
    workspace.laneWidth = laneWidth;
    const RateExtremes extremes = computeRates(p, list, model, workspace);
    const Reference ref = directSums(p, model);
    // Tolerances relative to the largest value: the sums cancel (pressure terms of ~50 pairs).
    const double scaleA = std::max({maxAbs(ref.ax), maxAbs(ref.ay), maxAbs(ref.az)}), scaleD = maxAbs(ref.drho);
    ASSERT_GT(scaleA, 0);
    ASSERT_GT(scaleD, 0);
    for (std::size_t a = 0; a < p.size(); ++a) {
      EXPECT_NEAR(p.ax[a], ref.ax[a], 1e-10 * scaleA) << "particle " << a << ", equal masses " << equalMasses
                                                       << ", " << laneWidth << " lanes";
      EXPECT_NEAR(p.ay[a], ref.ay[a], 1e-10 * scaleA) << "particle " << a;
      EXPECT_NEAR(p.az[a], ref.az[a], 1e-10 * scaleA) << "particle " << a;
      EXPECT_NEAR(p.drho[a], ref.drho[a], 1e-10 * scaleD) << "particle " << a;
    }
    EXPECT_NEAR(extremes.maxViscousMu, ref.maxMu, 1e-12 * ref.maxMu);
    // The walls' extrapolated pressure and its density, wet (fluid in reach) and dry (the floor's
    // lowest layer: p = 0, ρ = ρ0) alike.
    const double scaleP = maxAbs(ref.pressure);
    std::size_t wet = 0, dry = 0;
    for (std::size_t w = 0; w < p.size(); ++w) {
      if (p.isFluid(w)) continue;
      (ref.pressure[w] > 0 ? wet : dry) += 1;
      EXPECT_NEAR(p.pressure[w], ref.pressure[w], 1e-10 * scaleP) << "boundary particle " << w;
      EXPECT_NEAR(p.rhoEst[w], ref.rho[w], 1e-12 * model.eos.referenceDensity) << "boundary particle " << w;
    }
    EXPECT_GT(wet, 0u);
    EXPECT_GT(dry, 0u);
  }
}

TEST(SphPairLoop, RatesAreBitwiseIdenticalForFourAndEightLanes) {
  // Lane l of a block sums into lane l of the particle's sums at either width, and the 8 lanes are
  // added in one order (simd_lanes.hpp): the width is a matter of speed only. Every variant of the
  // loop: equal and unequal masses, with and without density diffusion, walls included.
#ifndef RUPTURE_SPH_AVX512
  GTEST_SKIP() << "built without AVX-512: one loop (the AVX2 lanes or the portable one) runs both widths";
#endif
  for (bool equalMasses : {true, false})
    for (DiffusionModel diffusion : {DiffusionModel::Fourtakas, DiffusionModel::Off}) {
      FluidModel model = testModel();
      model.diffusion = diffusion;
      ParticleArray<double> at4[5];
      for (int laneWidth : {4, 8}) {
        FluidParticles p = jitteredBlock(equalMasses, 14);
        NeighbourList list;
        list.build(p, 3, 1.1 * model.kernel().support());
        RateWorkspace workspace;
        workspace.laneWidth = laneWidth;
        const RateExtremes extremes = computeRates(p, list, model, workspace);
        EXPECT_GT(extremes.maxViscousMu, 0.0);
        if (laneWidth == 4) {
          at4[0] = p.ax;
          at4[1] = p.ay;
          at4[2] = p.az;
          at4[3] = p.drho;
          at4[4] = p.pressure;
          continue;
        }
        const std::string what = std::string(equalMasses ? "equal" : "unequal") + " masses, diffusion " +
                                 (diffusion == DiffusionModel::Off ? "off" : "on");
        EXPECT_EQ(p.ax, at4[0]) << what;
        EXPECT_EQ(p.ay, at4[1]) << what;
        EXPECT_EQ(p.az, at4[2]) << what;
        EXPECT_EQ(p.drho, at4[3]) << what;
        EXPECT_EQ(p.pressure, at4[4]) << what << " (the walls' extrapolated pressures)";
      }
    }
}

TEST(SphPairLoop, RatesAreBitwiseIdenticalForOneTwoAndFourThreads) {
  const FluidModel model = testModel();
  ParticleArray<double> first[4];
  for (int threads : {1, 2, 4}) {
    omp_set_num_threads(threads);
    FluidParticles p = jitteredBlock(true, 13);
    NeighbourList list;
    list.build(p, 3, 1.1 * model.kernel().support());
    RateWorkspace workspace;
    computeRates(p, list, model, workspace);
    if (threads == 1) {
      first[0] = p.ax;
      first[1] = p.ay;
      first[2] = p.az;
      first[3] = p.drho;
    } else {
      EXPECT_EQ(p.ax, first[0]) << threads << " threads";
      EXPECT_EQ(p.ay, first[1]) << threads << " threads";
      EXPECT_EQ(p.az, first[2]) << threads << " threads";
      EXPECT_EQ(p.drho, first[3]) << threads << " threads";
    }
  }
  omp_set_num_threads(1);
}

}  // namespace
}  // namespace rupture::sph
