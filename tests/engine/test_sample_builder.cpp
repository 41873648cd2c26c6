// Sample generation: porosity on target, pores that do not overlap, reproducibility, and the
// dense packing's coordination and density bookkeeping.
#include <gtest/gtest.h>

#include <cmath>

#include "samples/sample_builder.hpp"
#include "sample_test_support.hpp"

using namespace rupture;
using rupture::testing::ceramic;
using rupture::testing::porousSpec;

namespace {

class PorousSample : public ::testing::TestWithParam<int> {};

TEST_P(PorousSample, PorosityOnTargetAndPoresApart) {
  const SampleSpec spec = porousSpec(GetParam(), 7);
  BondedSystem system;
  const SampleReport report = buildSample(spec, ceramic(), system);
  EXPECT_NEAR(report.porosity, spec.porosity, 0.005 * spec.porosity);
  ASSERT_GE(report.pores.size(), 2u);
  for (std::size_t a = 0; a < report.pores.size(); ++a) {
    const Pore& pa = report.pores[a];
    for (int ax = 0; ax < spec.dimension; ++ax) {
      EXPECT_GE(pa.centre[ax] - pa.radius, 0.0);
      EXPECT_LE(pa.centre[ax] + pa.radius, spec.size[ax]);
    }
    for (std::size_t b = a + 1; b < report.pores.size(); ++b) {
      const Pore& pb = report.pores[b];
      double d2 = 0;
      for (int ax = 0; ax < 3; ++ax) d2 += std::pow(pa.centre[ax] - pb.centre[ax], 2);
      EXPECT_GE(std::sqrt(d2), pa.radius + pb.radius) << "pores " << a << " and " << b << " overlap";
    }
  }
  // No element centre is left inside a pore.
  const ParticleStore& p = system.particles;
  for (std::size_t k = 0; k < p.size(); ++k)
    for (const Pore& pore : report.pores) {
      const double d = std::hypot(p.x[k] - pore.centre[0], p.y[k] - pore.centre[1], p.z[k] - pore.centre[2]);
      ASSERT_GE(d, pore.radius * (1 - 1e-12));
    }
}

TEST_P(PorousSample, SameSeedSameSampleOtherSeedOtherSample) {
  BondedSystem a, b, c;
  buildSample(porousSpec(GetParam(), 42), ceramic(), a);
  buildSample(porousSpec(GetParam(), 42), ceramic(), b);
  buildSample(porousSpec(GetParam(), 43), ceramic(), c);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  EXPECT_EQ(a.particles.x, b.particles.x);
  EXPECT_EQ(a.particles.y, b.particles.y);
  EXPECT_EQ(a.particles.z, b.particles.z);
  EXPECT_EQ(a.particles.radius, b.particles.radius);
  EXPECT_EQ(a.bonds.i, b.bonds.i);
  EXPECT_EQ(a.bonds.j, b.bonds.j);
  EXPECT_NE(a.particles.x, c.particles.x);
}

INSTANTIATE_TEST_SUITE_P(TwoAndThreeD, PorousSample, ::testing::Values(2, 3));

TEST(DenseSample, BondsTouchingNeighboursAndKeepsBulkDensity) {
  SampleSpec spec = porousSpec(2, 3);
  spec.porosity = 0;
  BondedSystem system;
  const SampleReport report = buildSample(spec, ceramic(), system);
  EXPECT_EQ(report.porosity, 0.0);
  EXPECT_GT(report.meanCoordination, 4.0);  // a 2D random packing bonded at contact: about 4.5
  EXPECT_LT(report.meanCoordination, 6.0);
  double mass = 0;
  for (double m : system.particles.mass) mass += m;
  const double volume = spec.size[0] * spec.size[1] * report.thickness;
  EXPECT_NEAR(mass / volume, 6060.0, 1e-9 * 6060.0);
  // Every element lies inside the box and has at least one bond.
  const auto z = system.bonds.coordination(system.particles.size());
  for (std::size_t k = 0; k < system.particles.size(); ++k) {
    EXPECT_GE(z[k], 1);
    EXPECT_GE(system.particles.x[k], 0.0);
    EXPECT_LE(system.particles.x[k], spec.size[0]);
  }
}

}  // namespace
