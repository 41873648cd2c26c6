// The planar (2D) form of the beam bond loop, kick and drift (BondedSystem::planarMotion) against
// the 3D forms it specialises: the same law on in-plane data, and the same trajectory, breaks
// included, of a 2D sample stepped both ways.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "dem/beam_bond.hpp"
#include "samples/sample_builder.hpp"

using namespace rupture;

namespace {

/// A 0.15 µm square of the seed's elements (R_DE = 3.3 nm) and Table 3 beams.
SampleSpec smallSquare() {
  SampleSpec spec;
  spec.dimension = 2;
  spec.size = {0.15e-6, 0.15e-6, 0};
  spec.elementRadius = 3.3e-9;
  spec.seed = 5;
  return spec;
}

BondedSystem smallBeamSample() {
  MaterialSpec m;
  m.density = 6060;
  m.beam = {2865e9, 0.3, 0.3, 4e9};
  m.contact.youngModulus = 2865e9;
  BondedSystem system;
  buildSample(smallSquare(), m, system);
  return system;
}

/// |a − b| relative to the scale of the quantity (its largest magnitude over the cases).
void expectClose(double a, double b, double scale, const char* what) {
  EXPECT_LE(std::fabs(a - b), 1e-13 * scale) << what << ": planar " << a << ", 3D " << b;
}

}  // namespace

TEST(PlanarBeam, SameLoadsAsTheThreeDimensionalLawOnInPlaneData) {
  // Random in-plane bonds: chord and reference direction in the plane, ends rotated about z by up
  // to 0.2 rad, stretch up to ±1 %; both bending-moment rules.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (bool relative : {false, true}) {
    BeamParameters p{2865e9, 0.3, 0.3, 4e9, relative};
    for (int c = 0; c < 2000; ++c) {
      const double r = 3.3e-9, L0 = 2 * r * (1 + 0.1 * u(rng));
      const double a0 = std::numbers::pi * u(rng);
      const double n0x = std::cos(a0), n0y = std::sin(a0);
      const double a = a0 + 0.05 * u(rng), L = L0 * (1 + 0.01 * u(rng));
      const double dx = L * std::cos(a), dy = L * std::sin(a);
      const double thetaI = 0.2 * u(rng), thetaJ = 0.2 * u(rng);
      const double qiw = std::cos(thetaI / 2), qiz = std::sin(thetaI / 2);
      const double qjw = std::cos(thetaJ / 2), qjz = std::sin(thetaJ / 2);
      const BeamResponse full =
          beamResponse(p, r, r, L0, n0x, n0y, 0, dx, dy, 0, qiw, 0, 0, qiz, qjw, 0, 0, qjz);
      const PlanarBeamResponse planar = planarBeamResponse(p, r, r, L0, n0x, n0y, dx, dy, qiw, qiz, qjw, qjz);
      // The 3D law gives exact zeros out of the plane and no twist: the planar form drops them.
      EXPECT_EQ(full.fjz, 0.0);
      EXPECT_EQ(full.tix, 0.0);
      EXPECT_EQ(full.tiy, 0.0);
      EXPECT_EQ(full.tjx, 0.0);
      EXPECT_EQ(full.tjy, 0.0);
      EXPECT_EQ(full.twist, 0.0);
      const double force = std::hypot(full.fjx, full.fjy), moment = std::max(std::fabs(full.tiz), std::fabs(full.tjz));
      expectClose(planar.fjx, full.fjx, force, "F_x");
      expectClose(planar.fjy, full.fjy, force, "F_y");
      expectClose(planar.tiz, full.tiz, moment, "T_iz");
      expectClose(planar.tjz, full.tjz, moment, "T_jz");
      expectClose(planar.equivalentStress, full.equivalentStress, std::fabs(full.equivalentStress), "sigma_eq");
      const double energy = planarBeamEnergy(p, r, r, L0, n0x, n0y, dx, dy, qiw, qiz, qjw, qjz);
      expectClose(energy, full.energy, std::fabs(full.energy), "U");
    }
  }
}

TEST(PlanarBeam, TwoDimensionalSampleFollowsTheThreeDimensionalStep) {
  const SampleSpec spec = smallSquare();
  BondedSystem planar = smallBeamSample();
  ASSERT_TRUE(planar.planarMotion());

  // A stretching in-plane velocity field with random spins: beams bend, then break (the
  // failure strain σ_f / E is 0.14 %, the field stretches the sample by about 0.5 %).
  ParticleStore& p = planar.particles;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double rate = 1.5e8, dt = 0.5 * planar.criticalTimeStep();
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.vx[k] = rate * (p.x[k] - 0.5 * spec.size[0]);
    p.vy[k] = 0.3 * rate * (p.y[k] - 0.5 * spec.size[1]);
    p.wz[k] = 0.5 * rate * u(rng);
  }
  // The same system stepped with the 3D forms: as a 3D system it does not qualify for the planar path.
  BondedSystem full = planar;
  full.particles.dimension = 3;
  full.initialize();
  planar.initialize();
  ASSERT_FALSE(full.planarMotion());
  ASSERT_TRUE(planar.planarMotion());

  std::size_t brokenPlanar = 0, brokenFull = 0;
  for (int s = 0; s < 1500; ++s) {
    planar.step(dt);
    full.step(dt);
    brokenPlanar += planar.brokenLastStep;
    brokenFull += full.brokenLastStep;
  }
  EXPECT_GT(brokenPlanar, 0u);
  EXPECT_EQ(brokenPlanar, brokenFull);
  double worstPosition = 0, worstAngle = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    worstPosition = std::max({worstPosition, std::fabs(planar.particles.x[k] - full.particles.x[k]),
                              std::fabs(planar.particles.y[k] - full.particles.y[k])});
    worstAngle = std::max(worstAngle, std::fabs(planar.particles.qz[k] - full.particles.qz[k]));
    EXPECT_EQ(full.particles.z[k], planar.particles.z[k]);
    EXPECT_EQ(full.particles.qx[k], 0.0);
    EXPECT_EQ(full.particles.qy[k], 0.0);
  }
  // Rounding only (the two forms differ by the compiler's fused multiply-adds): far below the
  // displacements of the run (about 0.5 % of 0.15 µm).
  EXPECT_LT(worstPosition, 1e-9 * spec.elementRadius);
  EXPECT_LT(worstAngle, 1e-9);
}

TEST(PlanarBeam, LoadsEvaluatedAgainFromTheStateAreTheStepsOwnBitForBit) {
  // A decomposed run's whole system evaluates its bond loads again from the gathered positions
  // and orientations (BondedSystem::bondLoads after adoptGatheredState) for its snapshots: in
  // planar motion they must be the step's own planar loads to the last bit, breaks included.
  const SampleSpec spec = smallSquare();
  BondedSystem s = smallBeamSample();
  ParticleStore& p = s.particles;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double rate = 1.5e8, dt = 0.5 * s.criticalTimeStep();
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.vx[k] = rate * (p.x[k] - 0.5 * spec.size[0]);
    p.wz[k] = 0.5 * rate * u(rng);
  }
  s.initialize();
  ASSERT_TRUE(s.planarMotion());
  std::size_t broken = 0;
  for (int step = 0; step < 1500; ++step) {
    s.step(dt);
    broken += s.brokenLastStep;
  }
  ASSERT_GT(broken, 0u);
  const BondStore stepped = s.bondLoads();
  s.adoptGatheredState(s.time, s.steps);  // the loads are now stale: bondLoads evaluates them again
  const BondStore& again = s.bondLoads();
  for (std::size_t b = 0; b < stepped.size(); ++b) {
    ASSERT_EQ(std::memcmp(&again.fjx[b], &stepped.fjx[b], sizeof(double)), 0) << "bond " << b;
    ASSERT_EQ(std::memcmp(&again.fjy[b], &stepped.fjy[b], sizeof(double)), 0) << "bond " << b;
    ASSERT_EQ(std::memcmp(&again.failureMeasure[b], &stepped.failureMeasure[b], sizeof(double)), 0) << "bond " << b;
  }
}
