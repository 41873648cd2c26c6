#pragma once
// State of the bond network of a bonded sample: per-element damage and the fragments left at the
// end of a run. Both read only BondStore::intact and are O(elements + bonds).
#include <cstddef>
#include <vector>

#include "core/bond_store.hpp"

namespace rupture {

/// Damage index of each element (seed 003; LAMMPS damage/atom; physics-reference §3.6):
///   φ_i = Σ_j (1 − χ_ij) V_j / Σ_j V_j
/// over its initial bonds (every bond of the store, intact or not), χ = 1 intact, 0 broken, V_j the
/// partner's volume (all equal when `volume` is null: the fraction of broken bonds); 0 for an
/// element that never had a bond.
std::vector<double> elementDamage(const BondStore& bonds, std::size_t elementCount,
                                  const std::vector<double>* volume = nullptr);

/// Number of fragments: connected clusters of at least `minSize` elements linked by intact bonds
/// (union–find with path halving and union by size). An intact sample is one fragment.
std::size_t countFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minSize = 2);

}  // namespace rupture
