#pragma once
// Disorder of the bonds (material.disorder): random per-bond factors of mean 1 on each bond's
// strength (its critical value, in its criterion's measure) and on its stiffness, as the lattice
// models of heterogeneous brittle materials give their springs (Ostoja-Starzewski & Wang 2006's
// fluctuating Young's modulus and strength; Li, Pan & Sinka 2011's Weibull strengths; reviewed in
// Yu et al. 2019, docs/references.md#yu2019).
//
// The draws are counter-based: a bond's factor is a hash of (seed, stream, bond index), so it does
// not depend on the order the bonds are visited in, on the thread count or on the standard
// library's distributions (whose algorithms are implementation-defined), and the same spec gives
// the same factors on every platform.
#include <cstdint>

#include "bonded/sample_spec.hpp"

namespace rupture {

struct BondStore;

/// The streams a disorder draws from (independent of each other and of the sample's).
enum class DisorderStream : std::uint64_t { Strength = 1, Stiffness = 2 };

/// The factor of bond `index` drawn from `distribution` (1 when its kind is None):
/// - Weibull with modulus m and mean 1: F(x) = 1 − exp(−(x/λ)^m), λ = 1/Γ(1 + 1/m);
/// - normal with mean 1 and coefficient of variation c, truncated symmetrically at 1 ± 3c (a draw
///   outside is drawn again), which keeps the mean at 1 and every factor positive for c ≤ 0.3.
double disorderFactor(const FactorDistribution& distribution, std::uint64_t seed, DisorderStream stream,
                      std::uint64_t index);

/// The cumulative distribution of the factor, P(X ≤ x), the one disorderFactor samples.
double disorderCdf(const FactorDistribution& distribution, double x);

/// Multiplies each bond's strength (BondStore::strength) and stiffness (BondStore::stiffness) by its
/// factors. Call after the material style has set the bonds' constants, before finalize.
void applyBondDisorder(const BondDisorder& disorder, BondStore& bonds);

}  // namespace rupture
