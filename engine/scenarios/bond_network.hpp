#pragma once
// State of the bond network of a bonded sample: per-element damage and the fragments left at the
// end of a run. Both read only BondStore::intact and are O(elements + bonds).
#include <cstddef>
#include <vector>

#include "core/bond_store.hpp"

namespace rupture {

/// Damage of each element: the fraction of its initial bonds (every bond of the store, intact or
/// not) that are broken; 0 for an element that never had a bond.
std::vector<double> elementDamage(const BondStore& bonds, std::size_t elementCount);

/// Largest Rankine stress of the intact bonds over the failure stress (0 if unbreakable). It grows
/// about linearly with the load before the first break: runs use it to estimate their progress.
double maxStressRatio(const BondStore& bonds, double failureStress);

/// Number of fragments: connected clusters of at least `minSize` elements linked by intact bonds
/// (union–find with path halving and union by size). An intact sample is one fragment.
std::size_t countFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minSize = 2);

}  // namespace rupture
