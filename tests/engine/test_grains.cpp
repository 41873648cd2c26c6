// Voronoi grains (samples/grains.hpp): every element is in the grain of its nearest seed point, bonds
// across grain boundaries carry the boundary factor, and weak boundaries make the fracture
// intergranular.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "samples/grains.hpp"
#include "samples/sample_builder.hpp"

namespace rupture {
namespace {

SampleSpec packing(std::uint64_t seed, int grains, double factor) {
  SampleSpec s;
  s.dimension = 2;
  s.size = {2e-3, 1e-3, 0};
  s.elementRadius = 2e-5;
  s.seed = seed;
  s.grains = {grains, factor};
  return s;
}

SampleSpec lattice(std::uint64_t seed, int grains, double factor) {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "triangular";
  s.spacing = 1e-4;
  s.elementRadius = 0.5e-4;
  s.thickness = 1e-4;
  s.size = {6e-3, 3e-3, 0};
  s.seed = seed;
  s.grains = {grains, factor};
  return s;
}

MaterialSpec springs(double s0) {
  MaterialSpec m;
  m.model = "hookean";
  m.density = 2500;
  m.springs.youngModulus = 70e9;
  m.springs.poissonRatio = 0.25;
  m.springs.criterion = "critical_stretch";
  m.springs.criticalValue = s0;
  m.contact.enabled = false;
  return m;
}

TEST(Grains, EveryElementIsInTheGrainOfItsNearestSeedPoint) {
  for (std::uint64_t seed : {1, 2, 3}) {
    BondedSystem s;
    MaterialSpec m;
    m.density = 2500;
    m.beam = {100e9, 0.3, 0.5, 1e9};
    buildSample(packing(seed, 2, 1.0), m, s);
    for (int count : {2, 9, 60}) {
      const SampleSpec spec = packing(seed, count, 1.0);
      const auto seeds = grainSeeds(spec);
      const auto grain = voronoiGrains(spec, s.particles);
      std::set<std::int32_t> present;
      for (std::size_t k = 0; k < s.particles.size(); ++k) {
        double best = 1e300;
        for (const auto& q : seeds)
          best = std::min(best, std::hypot(s.particles.x[k] - q[0], s.particles.y[k] - q[1]));
        const auto& mine = seeds[grain[k]];
        ASSERT_DOUBLE_EQ(std::hypot(s.particles.x[k] - mine[0], s.particles.y[k] - mine[1]), best)
            << "seed " << seed << " count " << count << " element " << k;
        present.insert(grain[k]);
      }
      // A grain a few elements wide or more holds elements (its seed point is inside it).
      EXPECT_EQ(present.size(), static_cast<std::size_t>(count)) << "seed " << seed << " count " << count;
    }
  }
}

TEST(Grains, BoundaryBondsCarryTheFactorAndTheOthersDoNot) {
  const double factor = 0.4;
  BondedSystem s;
  const SampleSpec spec = lattice(5, 10, factor);
  buildSample(spec, springs(1e-3), s);
  const auto grain = voronoiGrains(spec, s.particles);
  std::size_t boundary = 0;
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    const bool across = grain[s.bonds.i[b]] != grain[s.bonds.j[b]];
    boundary += across;
    EXPECT_DOUBLE_EQ(s.bonds.failureThreshold[b], across ? factor * 1e-3 : 1e-3) << b;
  }
  EXPECT_GT(boundary, 0u);
  EXPECT_LT(boundary, s.bonds.size() / 4);
}

/// Pulls a lattice sample apart (faces at ±v, linear initial field) until it stops breaking bonds;
/// returns {grain-boundary bonds / all bonds, grain-boundary bonds / broken bonds}.
std::pair<double, double> pullApart(std::uint64_t seed, double factor) {
  BondedSystem s;
  const SampleSpec spec = lattice(seed, 12, factor);
  buildSample(spec, springs(2e-3), s);
  const auto grain = voronoiGrains(spec, s.particles);
  ParticleStore& p = s.particles;
  const double length = spec.size[0], v = 2.0;  // m/s at each face: a strain rate of 670 /s
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.vx[k] = v * (2 * p.x[k] / length - 1);
    if (p.x[k] < 0.6 * spec.spacing || p.x[k] > length - 0.6 * spec.spacing) p.fixedDofs[k] = kFixX;
  }
  s.prescribe = [&](ParticleStore& q, double) {
    for (std::size_t k = 0; k < q.size(); ++k)
      if (q.fixedDofs[k] & kFixX) q.vx[k] = q.x[k] < 0.5 * length ? -v : v;
  };
  const double dt = 0.5 * s.criticalTimeStep();
  const double strainEnd = 3 * 2e-3;  // well past the critical stretch: the sample has come apart
  const int steps = static_cast<int>(strainEnd * length / (2 * v) / dt);
  for (int k = 0; k < steps; ++k) s.step(dt);
  std::size_t boundary = 0, broken = 0, brokenBoundary = 0;
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    const bool across = grain[s.bonds.i[b]] != grain[s.bonds.j[b]];
    boundary += across;
    if (s.bonds.intact[b] < 0.5) {
      ++broken;
      brokenBoundary += across;
    }
  }
  EXPECT_GT(broken, 0u);
  return {static_cast<double>(boundary) / s.bonds.size(), broken ? static_cast<double>(brokenBoundary) / broken : 0.0};
}

TEST(Grains, WeakBoundariesMakeTheFractureIntergranular) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const auto [share, weak] = pullApart(seed, 0.3);
    const auto [same, even] = pullApart(seed, 1.0);
    EXPECT_LT(share, 0.25) << seed;
    // Weak boundaries: most broken bonds are boundary bonds, far above their share of all bonds;
    // with equal strengths the crack ignores the grains.
    EXPECT_GT(weak, 0.8) << "seed " << seed << " boundary share " << share;
    EXPECT_LT(even, 2 * share + 0.1) << "seed " << seed << " boundary share " << share;
  }
}

}  // namespace
}  // namespace rupture
