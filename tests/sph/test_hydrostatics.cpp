// A water column at rest in a tank, gravity ramped in from zero: it must settle to the hydrostatic
// pressure ρ0 g (H − y), keep its mass exactly and stay in the tank; δ-SPH must make the pressure
// field quieter about the hydrostatic line.
#include <gtest/gtest.h>

#include <cmath>

#include "sph_test_support.hpp"

namespace rupture::testing {
namespace {

constexpr double kGravity = 9.81;

struct ColumnResult {
  double midDepthPressure = 0;   ///< time average over the last 0.1 s of the mean over a band (Pa)
  double expectedMidDepth = 0;   ///< ρ0 g H/2 (Pa)
  double scatter = 0;            ///< RMS of p − ρ0 g (H − y) over fluid particles, last 0.1 s (Pa)
  double massBefore = 0, massAfter = 0;
  int maxOutside = 0;
};

/// Ramps gravity in over 0.1 s from a uniform density ρ0, then holds it to 0.5 s.
ColumnResult settleColumn(const std::string& diffusion) {
  const double width = 0.1, height = 0.2, dx = 0.005;
  const DamBreakSpec spec = parseDamBreakSpec(restingColumnSpec(width, height, dx, diffusion));
  sph::SphSystem s;
  const DamBreakLattice g = buildDamBreak(s, spec);
  for (double& rho : s.particles.rho) rho = s.model.eos.referenceDensity;  // start unloaded
  const double rho0 = s.model.eos.referenceDensity, H = g.H();
  s.model.gravity = {0, 0, 0};
  s.initialise();
  ColumnResult r;
  r.massBefore = s.fluidMass();
  r.expectedMidDepth = rho0 * kGravity * 0.5 * H;
  const double lo[3] = {0, 0, 0}, hi[3] = {g.L(), g.T(), 0};
  const double ramp = 0.1, end = 0.5, average = 0.1;
  int samples = 0, scatterSamples = 0;
  double scatter2 = 0;
  while (s.time < end) {
    s.model.gravity[1] = -kGravity * std::min(1.0, s.time / ramp);
    s.step(s.stableTimeStep(0.2));
    if ((s.steps % 50) == 0) r.maxOutside = std::max(r.maxOutside, particlesOutside(s, lo, hi));
    if (s.time < end - average) continue;
    double band = 0;
    int inBand = 0;
    for (std::size_t k = 0; k < s.particles.size(); ++k) {
      if (!s.particles.isFluid(k)) continue;
      const double p = s.model.eos.pressure(s.particles.rho[k]), y = s.particles.y[k];
      const double hydrostatic = rho0 * kGravity * (H - y);
      scatter2 += (p - hydrostatic) * (p - hydrostatic);
      ++scatterSamples;
      if (std::fabs(y - 0.5 * H) < dx) {
        band += p;
        ++inBand;
      }
    }
    r.midDepthPressure += band / inBand;
    ++samples;
  }
  r.midDepthPressure /= samples;
  r.scatter = std::sqrt(scatter2 / scatterSamples);
  r.massAfter = s.fluidMass();
  return r;
}

TEST(SphHydrostatics, ColumnSettlesToTheHydrostaticPressureAndKeepsItsMass) {
  const ColumnResult r = settleColumn("fourtakas");  // the default
  EXPECT_NEAR(r.midDepthPressure / r.expectedMidDepth, 1.0, 0.03)
      << "mid-depth " << r.midDepthPressure << " Pa, hydrostatic " << r.expectedMidDepth << " Pa";
  EXPECT_EQ(r.massAfter, r.massBefore);
  EXPECT_EQ(r.maxOutside, 0);
}

TEST(SphHydrostatics, DensityDiffusionQuietensThePressureField) {
  const ColumnResult off = settleColumn("off");
  EXPECT_EQ(off.maxOutside, 0);
  for (const char* model : {"fourtakas", "molteni_colagrossi"}) {
    const ColumnResult on = settleColumn(model);
    EXPECT_LT(on.scatter, off.scatter) << "RMS about the hydrostatic line: " << on.scatter << " Pa with " << model
                                       << ", " << off.scatter << " Pa without";
  }
}

}  // namespace
}  // namespace rupture::testing
