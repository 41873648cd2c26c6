// Failure criteria (engine/damage/) through the bonded loop, and the damage index.
#include <gtest/gtest.h>

#include <cmath>

#include "bonded/bonded_system.hpp"
#include "samples/sample_builder.hpp"
#include "scenarios/bonded/intact_network.hpp"

namespace rupture {
namespace {

constexpr double kL0 = 1e-3, kStiffness = 2e7;

/// Two particles joined by one bond with `model`, stiffness k and threshold; j displaced by (ux, uy).
BondedSystem pair(const BondModel& model, double threshold, double ux, double uy = 0.0) {
  BondedSystem s;
  s.particles.dimension = 3;
  s.particles.add(0, 0, 0, 0.5 * kL0);
  s.particles.add(kL0, 0, 0, 0.5 * kL0);
  s.particles.setMassFromDensity(2500, 0);
  s.bonds.add(s.particles, 0, 1);
  s.bonds.stiffness[0] = kStiffness;
  s.bonds.threshold[0] = threshold;
  s.model = model;
  s.particles.x[1] += ux;
  s.particles.y[1] += uy;
  s.initialize();  // evaluates the bond once: it breaks there if it must
  return s;
}

TEST(CriticalEnergy, ABondBreaksExactlyWhenItsEnergyReachesTheCriticalValue) {
  const BondModel model = BondModelOf<CentralSpringLaw, CriticalEnergyCriterion>{{}, {}};
  const double wc = 3e-4;  // J
  const double extension = std::sqrt(2 * wc / kStiffness);  // ½ k Δ² = w_c
  EXPECT_EQ(pair(model, wc, extension * (1 - 1e-9)).bonds.intact[0], 1.0);
  EXPECT_EQ(pair(model, wc, extension * (1 + 1e-9)).bonds.intact[0], 0.0);
  // Compressed bonds never break, whatever their energy (PeriLab's default).
  EXPECT_EQ(pair(model, wc, -10 * extension).bonds.intact[0], 1.0);
}

TEST(CriticalStretch, BreaksAtS0AndTheCompressionTermRaisesIt) {
  const double s0 = 2e-3;
  const BondModel plain = BondModelOf<CentralSpringLaw, CriticalStretchCriterion>{{}, {0.0}};
  EXPECT_EQ(pair(plain, s0, s0 * kL0 * (1 - 1e-9)).bonds.intact[0], 1.0);
  EXPECT_EQ(pair(plain, s0, s0 * kL0 * (1 + 1e-9)).bonds.intact[0], 0.0);
}

TEST(StressThreshold, BreaksWhenTheNormalForceReachesSigmaTimesArea) {
  const BondModel model = BondModelOf<CentralSpringLaw, StressThresholdCriterion>{{}, {}};
  const double limit = 50.0;  // σ_c A_b (N)
  EXPECT_EQ(pair(model, limit, limit / kStiffness * (1 - 1e-9)).bonds.intact[0], 1.0);
  EXPECT_EQ(pair(model, limit, limit / kStiffness * (1 + 1e-9)).bonds.intact[0], 0.0);
  EXPECT_EQ(pair(model, limit, -100 * limit / kStiffness).bonds.intact[0], 1.0);
}

TEST(GriffithEnergy, APairInPureCompressionNeverBreaks) {
  const BondModel born = BondModelOf<BornLaw, GriffithEnergyCriterion>{{0.5}, {}};
  const double tiny = 1e-30;  // J: any crack-driving energy breaks the bond
  for (double squeeze : {1e-6, 1e-3, 0.2}) EXPECT_EQ(pair(born, tiny, -squeeze * kL0).bonds.intact[0], 1.0) << squeeze;
  // The same threshold breaks it in tension, and in shear (the shear spring's energy counts).
  EXPECT_EQ(pair(born, tiny, 1e-6 * kL0).bonds.intact[0], 0.0);
  EXPECT_EQ(pair(born, tiny, -1e-3 * kL0, 1e-4 * kL0).bonds.intact[0], 0.0);
  // Threshold exactness: tension energy ½ k_n Δ².
  const double wc = 1e-4, extension = std::sqrt(2 * wc / kStiffness);
  EXPECT_EQ(pair(born, wc, extension * (1 - 1e-9)).bonds.intact[0], 1.0);
  EXPECT_EQ(pair(born, wc, extension * (1 + 1e-9)).bonds.intact[0], 0.0);
}

TEST(NoFailureRegion, InfiniteStrengthKeepsTheBond) {
  BondedSystem s = pair(BondModelOf<CentralSpringLaw, CriticalStretchCriterion>{{}, {0.0}}, 1e-3, 0.0);
  s.bonds.strength[0] = std::numeric_limits<double>::infinity();
  s.particles.x[1] += 0.5 * kL0;  // stretch 0.5, far beyond s0
  s.initialize();
  EXPECT_EQ(s.bonds.intact[0], 1.0);
}

TEST(DamageIndex, HandBuiltNeighbourhoodGivesTheVolumeWeightedFraction) {
  // Site 0 bonded to 1, 2, 3 (volumes 1, 2, 3); 2 also bonded to 3. Break 0–2 and 2–3.
  BondStore b;
  ParticleStore p;
  p.dimension = 3;
  for (int k = 0; k < 4; ++k) p.add(k, 0, 0, 0.4);
  p.volume = {4.0, 1.0, 2.0, 3.0};
  b.add(p, 0, 1);
  b.add(p, 0, 2);
  b.add(p, 0, 3);
  b.add(p, 2, 3);
  b.finalize(p.size());
  b.intact[1] = 0;
  b.intact[3] = 0;
  const std::vector<double> phi = elementDamage(b, p.size(), &p.volume);
  EXPECT_DOUBLE_EQ(phi[0], 2.0 / 6.0);            // lost V_2 of V_1 + V_2 + V_3
  EXPECT_DOUBLE_EQ(phi[1], 0.0);
  EXPECT_DOUBLE_EQ(phi[2], 1.0);                  // both of its bonds
  EXPECT_DOUBLE_EQ(phi[3], 2.0 / (4.0 + 2.0));    // lost V_2 of V_0 + V_2
}

}  // namespace
}  // namespace rupture

namespace rupture {
namespace {

TEST(Interblock, CrossingBondsBreakAtTheirOwnValueInnerBondsDoNot) {
  // A 12 × 4 square lattice of Hookean springs: block 2 is the right half. Inside a block s0 = 1e-2;
  // from block 1 to 2 the interblock value 1e-3. A uniform stretch ε = 5e-3 along x.
  SampleSpec sample;
  sample.dimension = 2;
  sample.lattice = "square";
  sample.spacing = 1e-3;
  sample.thickness = 1e-3;
  sample.elementRadius = 0.5e-3;
  sample.size = {12e-3, 4e-3, 0};
  BlockRegion right;
  right.id = 2;
  right.box.min = {6e-3, -1.0, -1e308};
  right.box.max = {1.0, 1.0, 1e308};
  sample.blocks.push_back(right);
  MaterialSpec material;
  material.model = "hookean";
  material.density = 2500;
  material.springs.youngModulus = 70e9;
  material.springs.poissonRatio = 1.0 / 3.0;
  material.springs.criterion = "critical_stretch";
  material.springs.criticalValue = 1e-2;
  material.interblock[1 * 1000 + 2] = 1e-3;  // one orientation given: the bond breaks at it
  BondedSystem s;
  buildSample(sample, material, s);
  ParticleStore& p = s.particles;
  const double eps = 5e-3;
  for (std::size_t k = 0; k < p.size(); ++k) p.x[k] *= 1 + eps;
  s.initialize();
  std::size_t crossingBroken = 0, innerBroken = 0, crossingKept = 0;
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    const bool crossing = (p.x[s.bonds.i[b]] < 6e-3 * (1 + eps)) != (p.x[s.bonds.j[b]] < 6e-3 * (1 + eps));
    const double stretch = eps * s.bonds.n0x[b] * s.bonds.n0x[b];  // affine: ε n_x²
    const bool broken = s.bonds.intact[b] < 0.5;
    if (crossing && broken) ++crossingBroken;
    if (crossing && !broken) { ++crossingKept; EXPECT_LT(stretch, 1e-3 * 1.001); }
    if (!crossing && broken) ++innerBroken;
  }
  EXPECT_EQ(innerBroken, 0u);
  EXPECT_EQ(crossingBroken, 4u + 2u * 3u);  // 4 horizontal bonds, and the diagonals (stretch ε/2)
  EXPECT_EQ(crossingKept, 0u);
}

}  // namespace
}  // namespace rupture
