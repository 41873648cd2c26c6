#pragma once
// Verlet neighbour lists for the SPH pair loops, built on a uniform cell grid (counting sort).
// Full lists (each pair appears in both particles' lists) so the pair loop gathers into one
// particle at a time: no atomics, any thread count, the same sums in the same order. Each list
// holds the fluid neighbours first, then the boundary ones (a fluid particle only); boundary
// particles list only fluid neighbours, as boundary particles interact with fluid only.
// The cutoff is the kernel support plus a skin; SphSystem rebuilds when a particle has moved more
// than half the skin since the last build.
#include <cstdint>
#include <vector>

#include "sph/fluid_particles.hpp"

namespace rupture::sph {

class NeighbourList {
public:
  /// Builds the lists of every particle within `cutoff` (m). dimension 2 ignores z.
  void build(const FluidParticles& p, int dimension, double cutoff);

  /// A permutation that puts particles in cell order (z-, then y-, then x-major cells of edge
  /// `cellSize`), so that neighbours are close in memory: FluidParticles::permute(order).
  static std::vector<std::int32_t> cellOrder(const FluidParticles& p, int dimension, double cellSize);

  const std::int32_t* neighbours(std::size_t i) const { return m_index.data() + i * m_stride; }
  int count(std::size_t i) const { return m_count[i]; }
  int fluidCount(std::size_t i) const { return m_fluidCount[i]; }
  std::size_t totalPairs() const;  ///< Σ count (directed pairs)
  double cutoff() const { return m_cutoff; }

private:
  std::size_t m_stride = 0;
  double m_cutoff = 0;
  std::vector<std::int32_t> m_index, m_count, m_fluidCount;
  std::vector<std::int32_t> m_cellStart, m_sorted;
};

}  // namespace rupture::sph
