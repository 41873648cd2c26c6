// Second-phase inclusions (samples/inclusions.hpp): placement at the asked volume fraction without
// overlap, the per-bond and per-element properties they set, and an effective modulus inside the
// Voigt and Reuss bounds of the two phases.
#include <gtest/gtest.h>

#include <cmath>

#include "calibration/calibration.hpp"
#include "samples/inclusions.hpp"
#include "samples/sample_builder.hpp"

namespace rupture {
namespace {

constexpr double kSpacing = 1e-4;

SampleSpec lattice(std::uint64_t seed, double fraction, double stiffness = 1, double strength = 1,
                   double interface = 1, double density = 1) {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "triangular";
  s.spacing = kSpacing;
  s.elementRadius = 0.5 * kSpacing;
  s.thickness = kSpacing;
  s.size = {40 * kSpacing, 36 * kSpacing, 0};
  s.seed = seed;
  s.inclusions = {fraction, {3 * kSpacing, 5 * kSpacing}, stiffness, strength, interface, density};
  return s;
}

MaterialSpec springs() {
  MaterialSpec m;
  m.model = "hookean";
  m.density = 2500;
  m.springs.youngModulus = 70e9;
  m.springs.poissonRatio = 0.25;
  m.springs.criterion = "critical_stretch";
  m.springs.criticalValue = 1e-3;
  m.contact.enabled = false;
  return m;
}

double insideFraction(const std::vector<std::uint8_t>& inside) {
  double n = 0;
  for (auto v : inside) n += v;
  return n / static_cast<double>(inside.size());
}

TEST(Inclusions, PlacedWithoutOverlapAtTheAskedVolumeFraction) {
  for (std::uint64_t seed : {1, 2, 3}) {
    const SampleSpec spec = lattice(seed, 0.2);
    const std::vector<Pore> inclusions = placeInclusions(spec);
    double area = 0;
    for (std::size_t a = 0; a < inclusions.size(); ++a) {
      area += std::numbers::pi * inclusions[a].radius * inclusions[a].radius;
      for (int d = 0; d < 2; ++d) {  // inside the box
        EXPECT_GE(inclusions[a].centre[d] - inclusions[a].radius, 0.0);
        EXPECT_LE(inclusions[a].centre[d] + inclusions[a].radius, spec.size[d]);
      }
      for (std::size_t b = a + 1; b < inclusions.size(); ++b)
        EXPECT_GE(std::hypot(inclusions[a].centre[0] - inclusions[b].centre[0], inclusions[a].centre[1] - inclusions[b].centre[1]),
                  inclusions[a].radius + inclusions[b].radius);
    }
    const double box = spec.size[0] * spec.size[1];
    EXPECT_GE(area / box, 0.2);          // placed until the target is reached,
    EXPECT_LT(area / box, 0.2 + 0.02);   // by at most one more inclusion (π r_max² / box = 0.018)
    BondedSystem s;
    buildSample(spec, springs(), s);
    // Lattice sites inside the disks: the area fraction up to the disks' perimeter discretisation.
    EXPECT_NEAR(insideFraction(insideInclusions(inclusions, s.particles)), area / box, 0.03) << "seed " << seed;
  }
}

TEST(Inclusions, InclusionAndInterfaceBondsAndElementsGetTheirProperties) {
  const double a = 3.0, strength = 2.0, interface = 0.5, density = 1.5;
  BondedSystem plain, mixed;
  buildSample(lattice(7, 0.0), springs(), plain);
  const SampleSpec spec = lattice(7, 0.25, a, strength, interface, density);
  buildSample(spec, springs(), mixed);
  ASSERT_EQ(plain.bonds.size(), mixed.bonds.size());
  const auto inside = insideInclusions(placeInclusions(spec), mixed.particles);
  int counts[3] = {0, 0, 0};
  for (std::size_t b = 0; b < mixed.bonds.size(); ++b) {
    const int ends = inside[mixed.bonds.i[b]] + inside[mixed.bonds.j[b]];
    ++counts[ends];
    const double k = ends == 2 ? a : ends == 1 ? 2 * a / (1 + a) : 1.0;
    const double f = ends == 2 ? strength : ends == 1 ? interface : 1.0;
    EXPECT_DOUBLE_EQ(mixed.bonds.stiffness[b], k * plain.bonds.stiffness[b]) << b;
    EXPECT_DOUBLE_EQ(mixed.bonds.failureThreshold[b], f * plain.bonds.failureThreshold[b]) << b;
  }
  for (int e = 0; e < 3; ++e) EXPECT_GT(counts[e], 0) << e;
  for (std::size_t k = 0; k < mixed.particles.size(); ++k)
    EXPECT_DOUBLE_EQ(mixed.particles.mass[k], (inside[k] ? density : 1.0) * plain.particles.mass[k]) << k;
}

TEST(Inclusions, StiffInclusionsGiveAModulusBetweenTheVoigtAndReussBounds) {
  const double a = 4.0;
  for (std::uint64_t seed : {1, 2, 3}) {
    BondedSystem plain, mixed;
    buildSample(lattice(seed, 0.0), springs(), plain);
    const SampleSpec spec = lattice(seed, 0.2, a);
    buildSample(spec, springs(), mixed);
    const double f = insideFraction(insideInclusions(placeInclusions(spec), mixed.particles));
    const double matrix = measureElasticProperties(plain, lattice(seed, 0.0)).youngModulus;
    const double ratio = measureElasticProperties(mixed, spec).youngModulus / matrix;
    RecordProperty("ratio_seed" + std::to_string(seed), std::to_string(ratio) + " f " + std::to_string(f));
    // Same ν in both phases: E between the Reuss (series) and Voigt (parallel) mixtures.
    EXPECT_GT(ratio, 1.0 / (1 - f + f / a)) << "seed " << seed << " f " << f;
    EXPECT_LT(ratio, 1 - f + f * a) << "seed " << seed << " f " << f;
  }
}

}  // namespace
}  // namespace rupture
