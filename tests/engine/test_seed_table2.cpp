// Seed 000 (Longchamp et al., CSMA 2024), Table 2 on the seed's own sample, out of the box (issue
// #28 item 1): examples/dynamic-tension-seed.json as shipped (Table 1's 1 µm sample at R_DE = 3.3 nm,
// 11 % porosity, pores 0.05–0.15 µm, on the close-packed arrangement its element count implies;
// Table 3's beams; eq. 1's bending from the elements' relative rotation; stresses over 2 R_DE),
// measured by the quasi-static strength test (calibration/strength_test.hpp) on sample seeds 1–5.
// The means of ν, σ_R and the crack-onset strain are within 10 % of Table 2's porous row. E is the
// documented residual (docs/dynamic-tension.md, "Reproducing the seed's Table 2"): the close-packed
// matrix is 10 % stiffer than the seed's (242 against 220 GPa), so E is checked through what the
// pores do to it, the porous over the dense modulus, against Table 2's 150 / 220.
// Five 23,518-element samples and one dense sample: 545 s of a CI run's tests on a Zen 3 host
// (2026-12-07, 681b2c9; 1,445 s before the planar beam loop was vectorised there).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "calibration/calibration.hpp"
#include "calibration/strength_test.hpp"
#include "samples/sample_builder.hpp"
#include "scenarios/dynamic_tension/dynamic_tension_spec.hpp"
#include "test_dynamic_tension_support.hpp"

namespace rupture::test {
namespace {

// Table 2 (porous and dense rows) and the crack onset of the seed's §4 ("0,045 %").
constexpr double kSeedYoung = 150e9, kSeedPoisson = 0.32, kSeedStrength = 70e6, kSeedOnset = 4.5e-4;
constexpr double kSeedDenseYoung = 220e9, kSeedDensePoisson = 0.30;

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

TEST(SeedTable2, TheShippedSeedSampleOverFiveSampleSeeds) {
  const DynamicTensionSpec example = parseDynamicTensionSpec(readJson(examplePath("dynamic-tension-seed.json")));
  ASSERT_EQ(example.sample.spacing, 6.6e-9) << "the example is the seed's R_DE = 3.3 nm sample";

  SampleSpec dense = example.sample;
  dense.porosity = 0;
  BondedSystem denseSample;
  buildSample(dense, example.material, denseSample);
  const ElasticProperties matrix = measureElasticProperties(denseSample, dense);
  ASSERT_TRUE(matrix.converged);
  EXPECT_NEAR(matrix.poissonRatio, kSeedDensePoisson, 0.1 * kSeedDensePoisson);

  std::vector<double> young, poisson, strength, onset;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SampleSpec spec = example.sample;
    spec.seed = seed;
    BondedSystem sample;
    buildSample(spec, example.material, sample);
    const StrengthResult r = measureTensileStrength(sample, spec);
    ASSERT_TRUE(r.completed) << "sample seed " << seed;
    young.push_back(r.elastic.youngModulus);
    poisson.push_back(r.elastic.poissonRatio);
    strength.push_back(r.tensileStrength);
    onset.push_back(r.crackOnsetStrain);
    // Linear before the first break: the peak is at least E × onset strain.
    EXPECT_GE(r.tensileStrength, 0.97 * r.elastic.youngModulus * r.crackOnsetStrain) << "sample seed " << seed;
  }
  EXPECT_NEAR(mean(poisson), kSeedPoisson, 0.1 * kSeedPoisson);
  EXPECT_NEAR(mean(strength), kSeedStrength, 0.1 * kSeedStrength);
  EXPECT_NEAR(mean(onset), kSeedOnset, 0.1 * kSeedOnset);
  const double softening = mean(young) / matrix.youngModulus, seedSoftening = kSeedYoung / kSeedDenseYoung;
  EXPECT_NEAR(softening, seedSoftening, 0.1 * seedSoftening);
}

}  // namespace
}  // namespace rupture::test
