// Silling's local damping (core/local_damping.hpp; Bobaru et al. 2016 as PeriLab gives it): a
// damped bond decays at the rate of its dashpot, undamaged material is not damped, the damage index
// the damping reads is the one of the bond network, and it takes the energy out of the ringing left
// by a crack.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bonded/bonded_system.hpp"
#include "samples/sample_builder.hpp"
#include "scenarios/bonded/intact_network.hpp"

namespace rupture {
namespace {

constexpr double kBondLength = 1e-3, kBondStiffness = 2e7, kWaveSpeed = 5000.0;

/// Bond 0–1 intact; with `brokenNeighbours`, 0 and 1 also each lost a bond (to 2 and 3, far away),
/// so φ_0 = φ_1 = ½ (equal volumes). Particle 1 starts displaced by u0 along the bond.
BondedSystem dampedPair(double d, bool brokenNeighbours, double u0) {
  BondedSystem s;
  s.particles.dimension = 3;
  s.particles.add(0, 0, 0, 0.5 * kBondLength);
  s.particles.add(kBondLength, 0, 0, 0.5 * kBondLength);
  s.particles.add(0, 50 * kBondLength, 0, 0.5 * kBondLength);
  s.particles.add(kBondLength, 50 * kBondLength, 0, 0.5 * kBondLength);
  s.particles.setMassFromDensity(2500, 0);
  for (auto [a, b] : {std::pair{0, 1}, {0, 2}, {1, 3}}) {
    const std::size_t k = s.bonds.add(s.particles, a, b);
    s.bonds.stiffness[k] = kBondStiffness;
    s.bonds.threshold[k] = 1.0;  // s0 = 1: never reached here
    if (a != 0 || b != 1) s.bonds.intact[k] = brokenNeighbours ? 0.0 : 1.0;
  }
  if (!brokenNeighbours) {  // keep 2 and 3 bonded to nothing that moves: remove the two bonds
    s.bonds.filter({1, 0, 0});
  }
  s.model = BondModelOf<CentralSpringLaw, CriticalStretchCriterion>{{}, {0.0}};
  s.contact.setParameters({.enabled = false});
  s.bondDamping = d;
  s.dampingWaveSpeed = kWaveSpeed;
  s.particles.x[1] += u0;
  s.initialize();
  return s;
}

/// Successive maxima of the bond's extension over `periods` natural periods.
std::vector<double> extensionPeaks(BondedSystem& s, double period, int periods) {
  const double dt = period / 400;
  std::vector<double> peaks;
  double before = 0, now = s.particles.x[1] - s.particles.x[0] - kBondLength;
  for (int k = 0; k < 400 * periods; ++k) {
    s.step(dt);
    const double next = s.particles.x[1] - s.particles.x[0] - kBondLength;
    if (now > before && now >= next && now > 0) peaks.push_back(now);
    before = now;
    now = next;
  }
  return peaks;
}

TEST(LocalDamping, ADampedBondDecaysAtItsDashpotRate) {
  const double d = 0.2, u0 = 1e-6;
  BondedSystem s = dampedPair(d, true, u0);
  ASSERT_DOUBLE_EQ(s.damageIndex()[0], 0.5);
  ASSERT_DOUBLE_EQ(s.damageIndex()[1], 0.5);
  // μ ü + η u̇ + k u = 0, μ = m/2, η = φ̄ d k L0 / v0: envelope exp(−ζ ω_n t), ζ = η / (2 √(k μ)).
  const double mu = 0.5 * s.particles.mass[0], omega = std::sqrt(kBondStiffness / mu);
  const double eta = 0.5 * d * kBondStiffness * kBondLength / kWaveSpeed, zeta = eta / (2 * std::sqrt(kBondStiffness * mu));
  const double period = 2 * std::numbers::pi / (omega * std::sqrt(1 - zeta * zeta));
  const std::vector<double> peaks = extensionPeaks(s, period, 12);
  ASSERT_GE(peaks.size(), 10u);
  // Logarithmic decrement per period, from the first to the tenth peak: 2π ζ / √(1 − ζ²).
  const double measured = std::log(peaks[0] / peaks[9]) / 9;
  const double expected = 2 * std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta);
  EXPECT_NEAR(measured, expected, 0.03 * expected) << "zeta " << zeta;
}

TEST(LocalDamping, UndamagedMaterialIsNotDamped) {
  for (bool broken : {false, true}) {
    const double d = broken ? 0.0 : 0.2;  // intact neighbourhood with d > 0, or damage with d = 0
    BondedSystem s = dampedPair(d, broken, 1e-6);
    const double mu = 0.5 * s.particles.mass[0], period = 2 * std::numbers::pi * std::sqrt(mu / kBondStiffness);
    const std::vector<double> peaks = extensionPeaks(s, period, 12);
    ASSERT_GE(peaks.size(), 10u);
    EXPECT_NEAR(peaks[9] / peaks[0], 1.0, 1e-3) << (broken ? "d = 0" : "phi = 0");
  }
}

SampleSpec bar() {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "square";
  s.spacing = 1e-3;
  s.elementRadius = 0.5e-3;
  s.thickness = 1e-3;
  s.size = {30e-3, 10e-3, 0.0};
  return s;
}

MaterialSpec pmb(double d) {
  MaterialSpec m;
  m.model = "pmb";
  m.density = 2200;
  m.pmb.youngModulus = 72e9;
  m.pmb.criticalStretch = 0.1;  // unbreakable here: the cut is made by hand
  m.contact.enabled = false;
  m.localDamping = d;
  m.dampingWaveSpeed = std::sqrt(m.pmb.youngModulus / m.density);
  return m;
}

/// A stretched PMB bar released by cutting it in two at mid-length: each half rings. Returns the
/// mechanical energy (kinetic + bonds) at the cut and after each wave transit of the bar.
std::vector<double> ringingAfterACut(double d, int transits, std::vector<double>* damageCheck = nullptr) {
  BondedSystem s;
  const SampleSpec sample = bar();
  buildSample(sample, pmb(d), s);
  for (std::size_t k = 0; k < s.particles.size(); ++k) s.particles.x[k] *= 1 + 5e-4;  // below s0
  const double cut = 0.5 * sample.size[0];
  for (std::size_t b = 0; b < s.bonds.size(); ++b)
    if ((s.particles.x[s.bonds.i[b]] - cut) * (s.particles.x[s.bonds.j[b]] - cut) < 0) s.bonds.intact[b] = 0.0;
  s.initialize();
  if (damageCheck) *damageCheck = s.damageIndex();
  const double transit = sample.size[0] / std::sqrt(72e9 / 2200);
  const int stepsPerTransit = static_cast<int>(std::ceil(transit / (0.25 * s.criticalTimeStep())));
  const double dt = transit / stepsPerTransit;
  std::vector<double> energy{s.kineticEnergy() + s.bondEnergy()};
  for (int t = 0; t < transits; ++t) {
    for (int k = 0; k < stepsPerTransit; ++k) s.step(dt);
    energy.push_back(s.kineticEnergy() + s.bondEnergy());
  }
  return energy;
}

TEST(LocalDamping, TheDamageItReadsIsTheBondNetworksVolumeWeightedIndex) {
  std::vector<double> incremental;
  ringingAfterACut(1.0, 0, &incremental);
  BondedSystem s;
  buildSample(bar(), pmb(1.0), s);
  const double cut = 0.5 * bar().size[0];
  for (std::size_t b = 0; b < s.bonds.size(); ++b)
    if ((s.particles.x[s.bonds.i[b]] - cut) * (s.particles.x[s.bonds.j[b]] - cut) < 0) s.bonds.intact[b] = 0.0;
  const std::vector<double> counted = elementDamage(s.bonds, s.particles.size(), &s.particles.volume);
  ASSERT_EQ(incremental.size(), counted.size());
  int damaged = 0;
  for (std::size_t k = 0; k < counted.size(); ++k) {
    EXPECT_NEAR(incremental[k], counted[k], 1e-12) << k;
    damaged += counted[k] > 0;
  }
  EXPECT_GT(damaged, 0);
}

TEST(LocalDamping, TakesTheEnergyOutOfTheRingingAfterACrack) {
  const std::vector<double> free = ringingAfterACut(0.0, 12), damped = ringingAfterACut(1.0, 12);
  EXPECT_NEAR(free.front(), damped.front(), 1e-12 * free.front());  // the same released state
  for (double e : free) EXPECT_NEAR(e / free.front(), 1.0, 0.005);   // undamped: energy conserved
  // Damped: the dashpots only dissipate (energy never rises from one transit to the next), and the
  // ringing loses a large part of its energy within a few transits.
  for (std::size_t t = 1; t < damped.size(); ++t) EXPECT_LE(damped[t], damped[t - 1] * (1 + 1e-3)) << t;
  RecordProperty("damped_over_free", std::to_string(damped.back() / free.back()));
  EXPECT_LT(damped.back(), 0.75 * free.back()) << "damped/free " << damped.back() / free.back();
}

}  // namespace
}  // namespace rupture
