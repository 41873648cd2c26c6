// Disorder of the bonds (samples/bond_disorder.hpp, material.disorder): the factors follow the
// requested distribution (Kolmogorov–Smirnov), are reproducible from their seed and independent
// between strength and stiffness, reach the bonds of a built sample, leave a run bit for bit as it
// was at zero scatter, and Weibull strengths give the weakest-link size effect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "calibration/strength_test.hpp"
#include "samples/bond_disorder.hpp"
#include "sample_test_support.hpp"
#include "samples/sample_builder.hpp"

namespace rupture {
namespace {

FactorDistribution weibull(double m) {
  FactorDistribution d;
  d.kind = FactorDistribution::Kind::Weibull;
  d.weibullModulus = m;
  return d;
}

FactorDistribution normal(double cv) {
  FactorDistribution d;
  d.kind = FactorDistribution::Kind::Normal;
  d.variation = cv;
  return d;
}

/// The Kolmogorov–Smirnov statistic D = sup |F_n(x) − F(x)| of `sample` against `model`'s CDF.
double ksStatistic(std::vector<double> sample, const FactorDistribution& model) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double d = 0;
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const double f = disorderCdf(model, sample[k]);
    d = std::max({d, std::fabs(f - static_cast<double>(k) / n), std::fabs(static_cast<double>(k + 1) / n - f)});
  }
  return d;
}

/// The KS critical value at level α = 0.001 for n draws (asymptotic: 1.949 / √n).
double ksCritical(std::size_t n) { return 1.949 / std::sqrt(static_cast<double>(n)); }

std::vector<double> draws(const FactorDistribution& d, std::uint64_t seed, DisorderStream stream, std::size_t n) {
  std::vector<double> x(n);
  for (std::size_t k = 0; k < n; ++k) x[k] = disorderFactor(d, seed, stream, k);
  return x;
}

double mean(const std::vector<double>& x) { return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size()); }

double standardDeviation(const std::vector<double>& x) {
  const double mu = mean(x);
  double s = 0;
  for (double v : x) s += (v - mu) * (v - mu);
  return std::sqrt(s / static_cast<double>(x.size() - 1));
}

TEST(BondDisorder, FactorsFollowTheRequestedDistribution) {
  constexpr std::size_t n = 20000;
  for (std::uint64_t seed : {1, 2, 3}) {
    for (double m : {2.0, 6.0, 12.0}) {
      const std::vector<double> x = draws(weibull(m), seed, DisorderStream::Strength, n);
      EXPECT_LT(ksStatistic(x, weibull(m)), ksCritical(n)) << "Weibull m " << m << " seed " << seed;
      // The test can tell a neighbouring modulus apart (it is not passing everything).
      EXPECT_GT(ksStatistic(x, weibull(m * 1.25)), ksCritical(n)) << "Weibull m " << m << " seed " << seed;
      EXPECT_NEAR(mean(x), 1.0, 4 * standardDeviation(x) / std::sqrt(double(n)));
    }
    for (double cv : {0.05, 0.2, 0.3}) {
      const std::vector<double> x = draws(normal(cv), seed, DisorderStream::Stiffness, n);
      EXPECT_LT(ksStatistic(x, normal(cv)), ksCritical(n)) << "normal cv " << cv << " seed " << seed;
      EXPECT_GT(ksStatistic(x, normal(cv * 1.25)), ksCritical(n)) << "normal cv " << cv << " seed " << seed;
      EXPECT_NEAR(mean(x), 1.0, 4 * standardDeviation(x) / std::sqrt(double(n)));
      // Truncated at ±3 sd: the standard deviation is 0.9866 c (that of the truncated normal).
      EXPECT_NEAR(standardDeviation(x) / cv, 0.9866, 0.02) << cv;
      EXPECT_GE(*std::min_element(x.begin(), x.end()), 1 - 3 * cv);
      EXPECT_LE(*std::max_element(x.begin(), x.end()), 1 + 3 * cv);
    }
  }
}

TEST(BondDisorder, FactorsAreReproducibleAndIndependent) {
  constexpr std::size_t n = 20000;
  const std::vector<double> a = draws(weibull(6), 7, DisorderStream::Strength, n);
  EXPECT_EQ(a, draws(weibull(6), 7, DisorderStream::Strength, n));  // same seed: the same factors
  const std::vector<double> b = draws(weibull(6), 8, DisorderStream::Strength, n);
  const std::vector<double> c = draws(weibull(6), 7, DisorderStream::Stiffness, n);
  auto correlation = [&](const std::vector<double>& x, const std::vector<double>& y) {
    const double mx = mean(x), my = mean(y);
    double sxy = 0, sxx = 0, syy = 0;
    for (std::size_t k = 0; k < n; ++k) {
      sxy += (x[k] - mx) * (y[k] - my);
      sxx += (x[k] - mx) * (x[k] - mx);
      syy += (y[k] - my) * (y[k] - my);
    }
    return sxy / std::sqrt(sxx * syy);
  };
  // Another seed, another stream: uncorrelated (|r| < 4/√n, four standard errors).
  EXPECT_LT(std::fabs(correlation(a, b)), 4 / std::sqrt(double(n)));
  EXPECT_LT(std::fabs(correlation(a, c)), 4 / std::sqrt(double(n)));
  // Neighbouring bonds are uncorrelated too (the hash of consecutive indices).
  const std::vector<double> shifted(a.begin() + 1, a.end());
  const std::vector<double> head(a.begin(), a.end() - 1);
  EXPECT_LT(std::fabs(correlation(std::vector<double>(head.begin(), head.end() - 1),
                                  std::vector<double>(shifted.begin(), shifted.end() - 1))),
            4 / std::sqrt(double(n)));
}

SampleSpec triangularPlate(std::uint64_t seed) {
  SampleSpec s;
  s.dimension = 2;
  s.lattice = "triangular";
  s.spacing = 1e-4;
  s.elementRadius = 0.5e-4;
  s.thickness = 1e-4;
  s.size = {8e-3, 6e-3, 0};
  s.seed = seed;
  return s;
}

MaterialSpec bornSprings() {
  MaterialSpec m;
  m.model = "born";
  m.density = 2500;
  m.springs.youngModulus = 70e9;
  m.springs.poissonRatio = 0.2;
  m.springs.criterion = "critical_stretch";
  m.springs.criticalValue = 1e-3;
  return m;
}

TEST(BondDisorder, BondsOfABuiltSampleCarryTheirFactors) {
  MaterialSpec plain = bornSprings(), disordered = plain;
  disordered.disorder.seed = 11;
  disordered.disorder.strength = weibull(6);
  disordered.disorder.stiffness = normal(0.2);
  BondedSystem a, b;
  buildSample(triangularPlate(1), plain, a);
  buildSample(triangularPlate(1), disordered, b);
  ASSERT_EQ(a.bonds.size(), b.bonds.size());
  ASSERT_GT(a.bonds.size(), 10000u);
  std::vector<double> strength(b.bonds.size()), stiffness(b.bonds.size());
  for (std::size_t k = 0; k < b.bonds.size(); ++k) {
    strength[k] = b.bonds.failureThreshold[k] / a.bonds.failureThreshold[k];
    stiffness[k] = b.bonds.stiffness[k] / a.bonds.stiffness[k];
  }
  EXPECT_LT(ksStatistic(strength, weibull(6)), ksCritical(strength.size()));
  EXPECT_LT(ksStatistic(stiffness, normal(0.2)), ksCritical(stiffness.size()));
  // The time step follows the stiffest bonds.
  EXPECT_LT(b.criticalTimeStep(), a.criticalTimeStep());
}

/// A run of a notched Born plate pulled at its two x faces; returns the final positions and the
/// intact flags.
std::pair<std::vector<double>, std::vector<double>> pullPlate(const MaterialSpec& material) {
  SampleSpec spec = triangularPlate(3);
  spec.notches.push_back({{0, 3e-3, 0}, {1.5e-3, 3e-3, 0}});
  BondedSystem s;
  buildSample(spec, material, s);
  const TensionFaces faces = tensionFaces(s.particles);
  s.prescribe = [&faces](ParticleStore& p, double) {
    for (std::size_t k : faces.xmin) p.vx[k] = -5.0;
    for (std::size_t k : faces.xmax) p.vx[k] = 5.0;
  };
  s.initialize();
  const double dt = 0.5 * s.criticalTimeStep();
  for (int step = 0; step < 1000; ++step) s.step(dt);
  std::vector<double> state(s.particles.x);
  state.insert(state.end(), s.particles.y.begin(), s.particles.y.end());
  return {state, s.bonds.intact};
}

TEST(BondDisorder, ZeroScatterIsBitForBitNoDisorder) {
  MaterialSpec plain = bornSprings(), zero = plain;
  zero.disorder.strength = normal(0.0);
  zero.disorder.stiffness = normal(0.0);
  const auto a = pullPlate(plain), b = pullPlate(zero);
  EXPECT_EQ(a.first, b.first);
  EXPECT_EQ(a.second, b.second);
  EXPECT_LT(std::count(a.second.begin(), a.second.end(), 1.0), static_cast<long>(a.second.size()));  // it broke
  // and a real scatter changes the run.
  MaterialSpec scattered = plain;
  scattered.disorder.strength = normal(0.2);
  EXPECT_NE(pullPlate(scattered).second, a.second);
}

}  // namespace
}  // namespace rupture

namespace rupture {
namespace {

using testing::squareBeamLattice;

MaterialSpec weibullBeams(double m, std::uint64_t seed) {
  MaterialSpec material = testing::glassBeams();
  material.disorder.seed = seed;
  material.disorder.strength = weibull(m);
  return material;
}

struct Replicates {
  std::vector<double> onset, strength;
  double loadedBonds = 0;  ///< bonds along x: the ones the tension loads (the y bonds carry none)
};

Replicates strengthTests(int size, double m, int count) {
  Replicates r;
  const SampleSpec spec = squareBeamLattice(size, size);
  for (int seed = 1; seed <= count; ++seed) {
    BondedSystem s;
    buildSample(spec, weibullBeams(m, static_cast<std::uint64_t>(seed)), s);
    const StrengthResult result = measureTensileStrength(s, spec);
    EXPECT_TRUE(result.completed);
    r.onset.push_back(result.crackOnsetStrain);
    r.strength.push_back(result.tensileStrength);
    r.loadedBonds = 0;
    for (std::size_t b = 0; b < s.bonds.size(); ++b) r.loadedBonds += std::fabs(s.bonds.n0x[b]) > 0.5 ? 1 : 0;
  }
  return r;
}

/// The ratio of two replicate means and its standard error (first-order propagation).
std::pair<double, double> ratioOfMeans(const std::vector<double>& a, const std::vector<double>& b) {
  const double ma = mean(a), mb = mean(b);
  const double ea = standardDeviation(a) / std::sqrt(double(a.size())) / ma;
  const double eb = standardDeviation(b) / std::sqrt(double(b.size())) / mb;
  return {ma / mb, ma / mb * std::sqrt(ea * ea + eb * eb)};
}

// Weakest link (Weibull 1951): a bar of N equally loaded bonds whose strengths are Weibull of modulus
// m and mean 1 first breaks at the smallest, whose mean is N^(−1/m); two sizes' mean strengths are in
// the ratio (N2/N1)^(1/m). A square beam lattice pulled along x loads its x bonds alike. Ten
// replicates (sample seeds 1–10) of 12 × 12 and 24 × 24 elements; a mean must lie within 2.58
// standard errors (99 %) of the weakest-link value, the errors estimated from the replicates.
TEST(BondDisorder, WeibullStrengthsGiveTheWeakestLinkSizeEffect) {
  constexpr int kReplicates = 10;
  BondedSystem uniform;
  const SampleSpec small = squareBeamLattice(12, 12);
  MaterialSpec noScatter = weibullBeams(6, 1);
  noScatter.disorder = {};
  buildSample(small, noScatter, uniform);
  const double onsetUniform = measureTensileStrength(uniform, small).crackOnsetStrain;
  for (double m : {6.0, 12.0}) {
    const Replicates a = strengthTests(12, m, kReplicates), b = strengthTests(24, m, kReplicates);
    const double expected = std::pow(b.loadedBonds / a.loadedBonds, 1.0 / m);
    // The first break: the weakest of the loaded bonds, N^(−1/m) of the uniform onset on average.
    const double onsetMean = mean(a.onset) / onsetUniform;
    const double onsetError = standardDeviation(a.onset) / std::sqrt(double(kReplicates)) / onsetUniform;
    EXPECT_NEAR(onsetMean, std::pow(a.loadedBonds, -1.0 / m), 2.58 * onsetError) << "m " << m;
    const auto [onsetRatio, onsetRatioError] = ratioOfMeans(a.onset, b.onset);
    EXPECT_NEAR(onsetRatio, expected, 2.58 * onsetRatioError) << "m " << m;
    // The strength (the peak of the settled stress): the same scaling, the brittle lattice failing
    // soon after its weakest bond.
    const auto [ratio, ratioError] = ratioOfMeans(a.strength, b.strength);
    RecordProperty("m" + std::to_string(int(m)), "strength ratio " + std::to_string(ratio) + " +- " +
                                                     std::to_string(ratioError) + ", weakest link " + std::to_string(expected));
    EXPECT_NEAR(ratio, expected, 2.58 * ratioError) << "m " << m;
    EXPECT_GT(ratio, 1.0 + 2.58 * ratioError) << "m " << m;  // a size effect is there at all
  }
}

}  // namespace
}  // namespace rupture
