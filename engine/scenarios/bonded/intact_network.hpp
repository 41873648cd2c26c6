#pragma once
// State of the bond network of a bonded sample: per-element damage, the connected pieces left by
// the broken bonds (fragments and debris), whether two groups of elements are still joined, and
// the number of cracks crossing a section. All read only BondStore::intact and are
// O(elements + bonds) (cracksCrossing: O(elements × lines hit per element)).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bond_store.hpp"
#include "core/particle_store.hpp"

namespace rupture {

/// Damage index of each element (PeriLab; LAMMPS damage/atom; docs/references.md#eq-pd):
///   φ_i = Σ_j (1 − χ_ij) V_j / Σ_j V_j
/// over its initial bonds (every bond of the store, intact or not), χ = 1 intact, 0 broken, V_j the
/// partner's volume (all equal when `volume` is null: the fraction of broken bonds); 0 for an
/// element that never had a bond.
std::vector<double> elementDamage(const BondStore& bonds, std::size_t elementCount,
                                  const std::vector<double>* volume = nullptr);

/// Connected components of the elements through intact bonds (union–find with path halving and
/// union by size). An element with no intact bond is a component of one.
class BondComponents {
public:
  BondComponents(const BondStore& bonds, std::size_t elementCount);
  /// Representative element of k's component (the same for every element of it).
  std::size_t root(std::size_t k);
  /// Elements of the component whose representative is `root`.
  std::size_t size(std::size_t root) const { return m_size[root]; }
  std::size_t elementCount() const { return m_parent.size(); }

private:
  std::vector<std::size_t> m_parent, m_size;
};

/// Whether a path of intact bonds joins some element of `a` to some element of `b`.
bool groupsConnected(const BondStore& bonds, std::size_t elementCount, const std::vector<std::int32_t>& a,
                     const std::vector<std::int32_t>& b);

/// The pieces of a broken sample. Macroscopic fragments are the components of at least
/// `minFragmentSize` elements; every smaller component (single elements included) is debris.
struct FragmentAnalysis {
  std::vector<std::int64_t> fragmentSizes;  ///< elements per fragment, largest first
  std::vector<std::int32_t> elementFragment; ///< per element: index in fragmentSizes, −1 for debris
  std::size_t debris = 0;                   ///< number of debris components
  std::size_t debrisElements = 0;           ///< elements in them
};

FragmentAnalysis analyseFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minFragmentSize);

/// Number of fragments: connected clusters of at least `minSize` elements linked by intact bonds.
/// An intact sample is one fragment.
std::size_t countFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minSize = 2);

/// Cracks crossing the section normal to x. Lines parallel to x are laid across the section, one
/// every `spacing` in y (2D: the lines y = const) or on a square grid of that spacing in (y, z)
/// (3D), from `margin` inside the lateral bounding box of the elements. `piece` gives each element
/// the piece of material it belongs to (a macroscopic fragment, or a loaded face whose elements are
/// debris), −1 to ignore it (debris: its elements lie in the cracks). A line that passes through
/// elements (distance to the line below their radius, at their positions in `p`) of m distinct
/// pieces crosses m − 1 cracks. The result is the median over the lines that meet a piece (lower
/// median); 0 if none does. Counting distinct pieces rather than changes along x makes the count
/// blind to the interleaving of the elements of a jagged crack's two faces; a crack that stops
/// inside the sample has the same fragment on both sides and does not count.
std::size_t cracksCrossing(const ParticleStore& p, int dimension, const std::vector<std::int32_t>& piece,
                           double spacing, double margin);

}  // namespace rupture
