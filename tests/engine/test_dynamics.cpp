// Physics checks of the integrated system: energy conservation without damping or failure, and
// the speed of a pulse in a long bonded bar against √(E_macro/ρ) with E_macro from calibration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <omp.h>

#include "core/parallel.hpp"
#include "calibration/calibration.hpp"

using namespace rupture;

namespace {

MaterialSpec elasticCeramic() {
  MaterialSpec m;
  m.density = 6060;
  m.beam = {2865e9, 0.3, 0.3, 0.0};  // σ_f = 0: unbreakable
  m.contact.youngModulus = 2865e9;
  return m;
}

class EnergyConservation : public ::testing::TestWithParam<int> {};

TEST_P(EnergyConservation, KineticPlusElasticConstantOver10000Steps) {
  SampleSpec spec;
  spec.dimension = GetParam();
  spec.size = spec.dimension == 2 ? std::array<double, 3>{0.2e-6, 0.2e-6, 0} : std::array<double, 3>{0.06e-6, 0.06e-6, 0.06e-6};
  spec.elementRadius = 3.3e-9;
  BondedSystem s;
  buildSample(spec, elasticCeramic(), s);
  ParticleStore& p = s.particles;
  // A smooth initial velocity field (lowest extension and shear modes) plus a small spin.
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.vx[k] = 0.5 * std::sin(std::numbers::pi * p.x[k] / spec.size[0]);
    p.vy[k] = 0.3 * std::cos(std::numbers::pi * p.x[k] / spec.size[0]);
    p.wz[k] = 1e6 * std::sin(std::numbers::pi * p.y[k] / spec.size[1]);
  }
  const double dt = 0.15 * s.criticalTimeStep();
  const double e0 = s.kineticEnergy() + s.elasticEnergy();
  ASSERT_GT(e0, 0.0);
  double worst = 0;
  for (int step = 1; step <= 10000; ++step) {
    s.step(dt);
    if (step % 250 == 0) worst = std::max(worst, std::abs(s.kineticEnergy() + s.elasticEnergy() - e0) / e0);
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_EQ(s.bonds.intactCount(), s.bonds.size());
  EXPECT_GT(s.elasticEnergy(), 0.0);  // energy really moved between kinetic and elastic
}

INSTANTIATE_TEST_SUITE_P(TwoAndThreeD, EnergyConservation, ::testing::Values(2, 3));

TEST(WaveSpeed, PulseInALongBarTravelsAtBarSpeed) {
  SampleSpec spec;
  spec.dimension = 2;
  spec.elementRadius = 3.3e-9;
  // Long against the pulse, and wide enough (30 R) that the strip behaves as a continuum across
  // (narrower strips of a random packing are dominated by their free edges).
  spec.size = {800 * spec.elementRadius, 30 * spec.elementRadius, 0};
  BondedSystem bar;
  buildSample(spec, elasticCeramic(), bar);
  const double young = measureElasticProperties(bar, spec).youngModulus;
  const double barSpeed = std::sqrt(young / 6060.0);  // the dense sample has the bulk density

  // A smooth half-sine velocity pulse of the left end, long against the elements, short against the bar.
  BondedSystem s = bar;
  ParticleStore& p = s.particles;
  std::vector<std::size_t> left;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.x[k] - p.radius[k] < 0.6 * spec.elementRadius) { left.push_back(k); p.fixedDofs[k] = kFixX; }
  const double pulse = 120 * spec.elementRadius / barSpeed, amplitude = 1.0;
  s.prescribe = [&](ParticleStore& q, double t) {
    const double v = t < pulse ? amplitude * std::sin(std::numbers::pi * t / pulse) : 0.0;
    for (std::size_t k : left) q.vx[k] = v;
  };
  // Stations at 1/3 and 2/3 of the bar: the arrival time of the pulse's peak (mean x-velocity of a slice).
  const double stations[2] = {spec.size[0] / 3, 2 * spec.size[0] / 3};
  double peakTime[2] = {0, 0}, peakValue[2] = {0, 0};
  const double dt = 0.15 * s.criticalTimeStep();
  const double duration = pulse + 1.05 * spec.size[0] * 2 / 3 / barSpeed;
  while (s.time < duration) {
    s.step(dt);
    for (int a = 0; a < 2; ++a) {
      double sum = 0;
      int count = 0;
      for (std::size_t k = 0; k < p.size(); ++k)
        if (std::abs(p.x[k] - stations[a]) < 4 * spec.elementRadius) { sum += p.vx[k]; ++count; }
      const double mean = sum / count;
      if (mean > peakValue[a]) { peakValue[a] = mean; peakTime[a] = s.time; }
    }
  }
  ASSERT_GT(peakValue[1], 0.2 * amplitude);
  const double measured = (stations[1] - stations[0]) / (peakTime[1] - peakTime[0]);
  EXPECT_NEAR(measured, barSpeed, 0.03 * barSpeed) << "E_macro = " << young << " measured " << measured << " peaks " << peakValue[0] << " " << peakValue[1] << " at " << peakTime[0] << " " << peakTime[1];
}

}  // namespace

namespace {

// Same spec, same seed: the same trajectory bit for bit, whatever the thread count (each bond and
// each particle is summed by one thread in a fixed order; no atomics, no reductions in the step).
TEST(Determinism, TrajectoryIsIdenticalOnOneAndTwoThreads) {
  SampleSpec spec;
  spec.dimension = 3;
  spec.size = {0.12e-6, 0.12e-6, 0.12e-6};
  spec.elementRadius = 4e-9;  // > 8192 bonds: the bond loops really fork
  MaterialSpec m = elasticCeramic();
  m.beam.failureStress = 3e9;  // some bonds break, contacts start
  BondedSystem start;
  buildSample(spec, m, start);
  ASSERT_GT(start.bonds.size(), kMinParallelItems);
  for (std::size_t k = 0; k < start.particles.size(); ++k)
    start.particles.vx[k] = 40.0 * (start.particles.x[k] / spec.size[0] - 0.5);  // stretch it
  const double dt = 0.15 * start.criticalTimeStep();
  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    BondedSystem s = start;
    for (int step = 0; step < 300; ++step) s.step(dt);
    omp_set_num_threads(1);
    return s;
  };
  const BondedSystem one = run(1), two = run(2), twoAgain = run(2);
  EXPECT_GT(one.bonds.size() - one.bonds.intactCount(), 0u);
  EXPECT_EQ(one.bonds.intact, two.bonds.intact);
  EXPECT_EQ(one.particles.x, two.particles.x);
  EXPECT_EQ(one.particles.vy, two.particles.vy);
  EXPECT_EQ(one.particles.qz, two.particles.qz);
  EXPECT_EQ(two.particles.x, twoAgain.particles.x);
}

}  // namespace
