// Seed 000 (Longchamp et al., CSMA 2024), Table 2 from Table 1 and Table 3 (issue 13): the seed's
// porous sample on the close-packed (triangular) arrangement its element count implies, with
// Table 3's beams and S = L × R_DE (eq. 4), measured by the quasi-static strength test
// (calibration/strength_test.hpp). docs/dynamic-tension.md, "Reproducing the seed's Table 2": over five
// sample seeds the mean ν and σ_R / E and the median crack-onset strain are within 10 % of the
// seed's; E and σ_R are within 10 % of twice the seed's (the documented residual: the seed's
// stresses correspond to a 2D thickness of 2 R_DE). The onset is a median because one weak site
// makes a sample break early (sample seed 1: 1.5e-4; the four others 4.4–4.6e-4, documented).
// Reduced sample: R_DE = 12 nm instead of 3.3 nm (same 1 µm box, pores and porosity), about 1,750
// elements.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "samples/sample_builder.hpp"
#include "calibration/strength_test.hpp"

namespace rupture {
namespace {

constexpr double kSeedYoung = 150e9, kSeedPoisson = 0.32, kSeedStrength = 70e6, kSeedOnset = 4.5e-4;
constexpr double kThicknessResidual = 2.0;  // docs/dynamic-tension.md, "Residual"

SampleSpec seedSample(std::uint64_t seed) {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "triangular";
  s.size = {1e-6, 1e-6, 0};
  s.spacing = 2.4e-8;          // 2 R_DE
  s.thickness = 1.2e-8;        // R_DE: S = L × R_DE (seed eq. 4)
  s.elementRadius = 1.2e-8;
  s.porosity = 0.11;
  s.poreRadius = {5e-8, 1.5e-7};
  s.seed = seed;
  return s;
}

MaterialSpec table3() {
  MaterialSpec m;
  m.model = "beam";
  m.density = 6060;
  m.beam = {2865e9, 0.3, 0.3, 4e9};
  m.contact.youngModulus = 2865e9 * 0.09;
  return m;
}

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(SeedTable2, PorousSampleOverFiveSampleSeeds) {
  std::vector<double> young, poisson, strength, onset, ratio;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const SampleSpec spec = seedSample(seed);
    BondedSystem sample;
    buildSample(spec, table3(), sample);
    const StrengthResult r = measureTensileStrength(sample, spec);
    ASSERT_TRUE(r.completed) << "sample seed " << seed;
    young.push_back(r.elastic.youngModulus);
    poisson.push_back(r.elastic.poissonRatio);
    strength.push_back(r.tensileStrength);
    onset.push_back(r.crackOnsetStrain);
    ratio.push_back(r.tensileStrength / r.elastic.youngModulus);
    // Linear before the first break: the peak is at least E × onset strain.
    EXPECT_GE(r.tensileStrength, 0.97 * r.elastic.youngModulus * r.crackOnsetStrain) << "sample seed " << seed;
  }
  EXPECT_NEAR(mean(poisson), kSeedPoisson, 0.1 * kSeedPoisson);
  EXPECT_NEAR(median(onset), kSeedOnset, 0.1 * kSeedOnset);
  EXPECT_NEAR(mean(ratio), kSeedStrength / kSeedYoung, 0.1 * kSeedStrength / kSeedYoung);
  EXPECT_NEAR(mean(young), kThicknessResidual * kSeedYoung, 0.1 * kThicknessResidual * kSeedYoung);
  EXPECT_NEAR(mean(strength), kThicknessResidual * kSeedStrength, 0.1 * kThicknessResidual * kSeedStrength);
}

}  // namespace
}  // namespace rupture
