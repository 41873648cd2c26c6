#include "samples/bond_disorder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/bond_store.hpp"

namespace rupture {

namespace {

// SplitMix64's finaliser (Steele, Lea & Flood 2014): a bijective mix whose outputs for
// consecutive inputs pass BigCrush; chained over the key's words it is a hash of the key.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// A uniform number in (0, 1) from the key (seed, stream, index, draw): the 53 high bits, centred
/// in their interval so neither 0 nor 1 comes out.
double uniform(std::uint64_t seed, DisorderStream stream, std::uint64_t index, std::uint64_t draw) {
  const std::uint64_t h = mix(mix(mix(mix(seed) ^ static_cast<std::uint64_t>(stream)) ^ index) ^ draw);
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

constexpr double kTruncation = 3.0;  // the normal factor's truncation, in standard deviations

double standardNormalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

}  // namespace

double disorderFactor(const FactorDistribution& d, std::uint64_t seed, DisorderStream stream, std::uint64_t index) {
  switch (d.kind) {
    case FactorDistribution::Kind::None:
      return 1.0;
    case FactorDistribution::Kind::Weibull: {
      // Inverse transform: x = λ (−ln(1 − u))^(1/m).
      const double scale = 1.0 / std::tgamma(1.0 + 1.0 / d.weibullModulus);
      return scale * std::pow(-std::log1p(-uniform(seed, stream, index, 0)), 1.0 / d.weibullModulus);
    }
    case FactorDistribution::Kind::Normal: {
      if (d.variation == 0) return 1.0;
      // Box–Muller on successive pairs of draws until one falls within ±3 sd (99.7 % do at once).
      for (std::uint64_t draw = 0;; draw += 2) {
        const double u1 = uniform(seed, stream, index, draw), u2 = uniform(seed, stream, index, draw + 1);
        const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
        if (std::fabs(z) <= kTruncation) return 1.0 + d.variation * z;
      }
    }
  }
  return 1.0;
}

double disorderCdf(const FactorDistribution& d, double x) {
  switch (d.kind) {
    case FactorDistribution::Kind::None:
      return x < 1.0 ? 0.0 : 1.0;
    case FactorDistribution::Kind::Weibull: {
      if (x <= 0) return 0.0;
      const double scale = 1.0 / std::tgamma(1.0 + 1.0 / d.weibullModulus);
      return -std::expm1(-std::pow(x / scale, d.weibullModulus));
    }
    case FactorDistribution::Kind::Normal: {
      if (d.variation == 0) return x < 1.0 ? 0.0 : 1.0;
      const double z = std::clamp((x - 1.0) / d.variation, -kTruncation, kTruncation);
      const double low = standardNormalCdf(-kTruncation), high = standardNormalCdf(kTruncation);
      return (standardNormalCdf(z) - low) / (high - low);
    }
  }
  return 0.0;
}

void applyBondDisorder(const BondDisorder& disorder, BondStore& bonds) {
  if (disorder.strength.kind != FactorDistribution::Kind::None)
    for (std::size_t b = 0; b < bonds.size(); ++b)
      bonds.strength[b] *= disorderFactor(disorder.strength, disorder.seed, DisorderStream::Strength, b);
  if (disorder.stiffness.kind != FactorDistribution::Kind::None)
    for (std::size_t b = 0; b < bonds.size(); ++b)
      bonds.stiffness[b] *= disorderFactor(disorder.stiffness, disorder.seed, DisorderStream::Stiffness, b);
}

}  // namespace rupture
