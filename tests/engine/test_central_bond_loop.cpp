// The central-force loop (core/central_bond_loop.hpp) against the generic bonded loop
// (core/bond_loop.hpp) on a PMB block torn apart by an initial velocity field, with the
// compression term α (nodal s_min) and with the critical-energy criterion: the same bonds break,
// the same trajectory bit for bit, the same damage; and the central loop's trajectory does not depend on the
// thread count; with the partner list in its compact form (a table of the distinct bond values,
// which a lattice has few of) and in its full form (one value per slot). Also the on-demand per-bond loads (BondedSystem::bondLoads) equal the generic
// loop's stored loads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "samples/sample_builder.hpp"

namespace rupture {
namespace {

BondedSystem tornBlock(const std::string& criterion, double horizonFactor = 3.015) {
  SampleSpec s;
  s.dimension = 3;
  s.lattice = "simple-cubic";
  s.spacing = 1e-3;
  s.elementRadius = 0.5e-3;
  s.size = {14e-3, 10e-3, 8e-3};
  MaterialSpec m;
  m.model = "pmb";
  m.density = 2200;
  m.pmb.youngModulus = 22e9;
  m.pmb.horizonFactor = horizonFactor;
  m.pmb.criterion = criterion;
  if (criterion == "critical_stretch") {
    m.pmb.criticalStretch = 5e-4;
    m.pmb.compressionFactor = 0.25;
  } else {
    m.pmb.fractureEnergy = 10.0;
  }
  m.contact.enabled = false;
  BondedSystem system;
  buildSample(s, m, system);
  for (std::size_t k = 0; k < system.particles.size(); ++k)  // stretch along x: bonds break mid-block
    system.particles.vx[k] = 4.0 * (system.particles.x[k] / s.size[0] - 0.5);
  return system;
}

BondedSystem run(BondedSystem s, bool central, int threads, bool compact = true) {
  omp_set_num_threads(threads);
  s.centralLoop = central;
  s.compactCentralList = compact;
  s.initialize();
  const double dt = 0.5 * s.criticalTimeStep();
  for (int step = 0; step < 150; ++step) s.step(dt);
  omp_set_num_threads(1);
  return s;
}

class CentralLoop : public ::testing::TestWithParam<std::string> {};

TEST_P(CentralLoop, BreaksTheSameBondsAsTheGenericLoopAndIsThreadCountIndependent) {
  const BondedSystem start = tornBlock(GetParam());
  ASSERT_GT(start.bonds.size(), kMinParallelItems);  // the loops really fork on two threads
  const BondedSystem generic = run(start, false, 1), one = run(start, true, 1), two = run(start, true, 2);
  const BondedSystem full = run(start, true, 1, false), fullTwo = run(start, true, 2, false);
  const std::size_t broken = generic.bonds.size() - generic.bonds.intactCount();
  EXPECT_GT(broken, 100u);
  EXPECT_LT(broken, generic.bonds.size() / 2);
  EXPECT_EQ(generic.bonds.intact, one.bonds.intact);
  EXPECT_EQ(generic.damageIndex(), one.damageIndex());
  EXPECT_EQ(generic.particles.x, one.particles.x);  // same sums in the same order: the same bits
  EXPECT_EQ(generic.particles.vx, one.particles.vx);
  EXPECT_EQ(one.particles.x, two.particles.x);
  EXPECT_EQ(one.particles.vx, two.particles.vx);
  EXPECT_EQ(one.bonds.intact, two.bonds.intact);
  EXPECT_EQ(generic.bonds.intact, full.bonds.intact);  // the full form of the partner list: the same
  EXPECT_EQ(generic.particles.x, full.particles.x);
  EXPECT_EQ(generic.particles.vx, full.particles.vx);
  EXPECT_EQ(full.particles.x, fullTwo.particles.x);
  EXPECT_EQ(full.bonds.intact, fullTwo.bonds.intact);

  // Loads on demand: the generic loop's stored loads (of a configuration equal up to rounding).
  const BondStore& onDemand = one.bondLoads();
  double forceScale = 0, forceError = 0, measureScale = 0, measureError = 0;
  for (std::size_t b = 0; b < generic.bonds.size(); ++b) {
    forceScale = std::max(forceScale, std::fabs(generic.bonds.fjx[b]));
    forceError = std::max(forceError, std::fabs(generic.bonds.fjx[b] - onDemand.fjx[b]));
    measureScale = std::max(measureScale, std::fabs(generic.bonds.failureMeasure[b]));
    measureError = std::max(measureError, std::fabs(generic.bonds.failureMeasure[b] - onDemand.failureMeasure[b]));
  }
  EXPECT_GT(forceScale, 0.0);
  EXPECT_LE(forceError, 1e-6 * forceScale);
  EXPECT_LE(measureError, 1e-6 * measureScale);
}

// A horizon of 4.5 spacings: up to 372 partners a particle, so the loop takes a particle's slots
// in several chunks (128 each) and carries its force sums from one chunk to the next (the sums of
// a chunk are taken during the next chunk's read pass, which may be the next particle's).
TEST(CentralLoopChunks, ParticlesWithMoreSlotsThanAChunkGiveTheGenericLoopsBitsToo) {
  BondedSystem start = tornBlock("critical_stretch", 4.5);
  std::vector<std::size_t> partners(start.particles.size(), 0);
  for (std::size_t b = 0; b < start.bonds.size(); ++b) {
    ++partners[start.bonds.i[b]];
    ++partners[start.bonds.j[b]];
  }
  const std::size_t most = *std::max_element(partners.begin(), partners.end());
  ASSERT_GT(most, 256u);  // three chunks or more
  const BondedSystem generic = run(start, false, 1), one = run(start, true, 1), two = run(start, true, 2);
  const BondedSystem full = run(start, true, 2, false);
  EXPECT_GT(generic.bonds.size() - generic.bonds.intactCount(), 100u);
  EXPECT_EQ(generic.bonds.intact, one.bonds.intact);
  EXPECT_EQ(generic.particles.x, one.particles.x);
  EXPECT_EQ(generic.particles.vx, one.particles.vx);
  EXPECT_EQ(one.particles.vx, two.particles.vx);
  EXPECT_EQ(generic.particles.vx, full.particles.vx);
  EXPECT_EQ(generic.bonds.intact, full.bonds.intact);
}

INSTANTIATE_TEST_SUITE_P(PmbCriteria, CentralLoop, ::testing::Values("critical_stretch", "critical_energy"));

}  // namespace
}  // namespace rupture
