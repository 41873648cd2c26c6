// Rankine failure of a beam: σ_eq = ½(σ_N + √(σ_N² + 4τ²)) (seed eq. 1), with σ_N the traction plus
// the largest end bending stress and τ the torsion stress, and breaking at σ_eq >= σ_f.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "dem/beam_forces.hpp"
#include "bonded/bonded_system.hpp"

using namespace rupture;

namespace {

constexpr double kRadius = 1e-3, kE = 70e9, kNu = 0.25, kRatio = 0.5, kL0 = 2 * kRadius;
const double kR = kRatio * kRadius;
const double kS = std::numbers::pi * kR * kR, kI = std::numbers::pi * std::pow(kR, 4) / 4, kJ = 2 * kI;
const double kG = kE / (2 * (1 + kNu));

struct OneBond {
  BondedSystem s;
  explicit OneBond(double failureStress) {
    s.particles.dimension = 3;
    s.particles.add(0, 0, 0, kRadius);
    s.particles.add(kL0, 0, 0, kRadius);
    s.particles.setMassFromDensity(2500, 0);
    s.bonds.add(s.particles, 0, 1);
    s.beam = {kE, kNu, kRatio, failureStress};
  }
};

TEST(Rankine, EquivalentStressFormula) {
  EXPECT_DOUBLE_EQ(rankineEquivalentStress(3.0, 2.0), 0.5 * (3.0 + 5.0));
  EXPECT_DOUBLE_EQ(rankineEquivalentStress(5.0, 0.0), 5.0);
  EXPECT_DOUBLE_EQ(rankineEquivalentStress(-5.0, 0.0), 0.0);  // pure compression never breaks
}

TEST(Rankine, MixedTractionBendingTorsionMatchesEquationOne) {
  OneBond b(1e12);
  ParticleStore& p = b.s.particles;
  const double stretch = 2e-8, theta = 3e-5, psi = 4e-5;
  p.x[1] += stretch;
  const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitX())) *
                               Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  p.qw[1] = q.w(); p.qx[1] = q.x(); p.qy[1] = q.y(); p.qz[1] = q.z();
  b.s.bonds.finalize(2);
  const BeamResponse r = beamResponseOf(b.s.beam, p, b.s.bonds, 0);
  // Closed form: the end rotation θ of j gives moments 4EIθ/L (at j) and 2EIθ/L (at i).
  const double normal = kE * stretch / kL0 + (4 * kE * kI * theta / kL0) * kR / kI;
  const double shear = (kG * kJ * psi / kL0) * kR / kJ;
  const double expected = 0.5 * (normal + std::sqrt(normal * normal + 4 * shear * shear));
  EXPECT_NEAR(r.equivalentStress, expected, 1e-6 * expected);
}

TEST(Rankine, BondBelowThresholdSurvivesAboveBreaks) {
  const double stretch = 1e-8;
  const double sigma = kE * stretch / kL0;  // pure traction: σ_eq = N / S
  for (double factor : {1.0 + 1e-6, 1.0 - 1e-6}) {
    OneBond b(sigma * factor);
    b.s.particles.x[1] += stretch;
    b.s.initialize();
    const bool survives = factor > 1.0;
    EXPECT_EQ(b.s.bonds.intact[0] > 0.5, survives) << "threshold factor " << factor;
    EXPECT_EQ(b.s.brokenLastStep, survives ? 0u : 1u);
    // A broken bond carries nothing, and stays broken when unloaded.
    if (!survives) {
      EXPECT_EQ(b.s.particles.fx[1], 0.0);
      b.s.particles.x[1] -= stretch;
      b.s.step(1e-12);
      EXPECT_LT(b.s.bonds.intact[0], 0.5);
    } else {
      EXPECT_NEAR(b.s.particles.fx[1], -sigma * kS, 1e-9 * sigma * kS);
    }
  }
}

}  // namespace
