#pragma once
// Verlet neighbour lists for the SPH pair loops, built on a uniform cell grid (counting sort).
// Half lists: every interacting pair is listed once, by a fluid particle: a fluid–fluid pair by the
// particle whose grid cell comes first (the one of lower index within a cell), a fluid–wall pair
// by its fluid particle. A fluid particle's list holds those fluid neighbours first, then all its
// boundary neighbours; the pair loop computes each pair once and adds it to both particles
// (fluid_rates.cpp). The scan for fluid–fluid pairs covers only the cells after a particle's own
// (half the stencil); the particles of one cell and kind are scanned together, sharing the loads of
// their candidate rows. Boundary particles interact with fluid only; a boundary particle's list
// holds all its fluid neighbours, for the pressure extrapolation only (those pairs are also in the
// fluid particles' lists).
// The cutoff is the kernel support plus a skin; SphSystem rebuilds when interacting particles may
// have closed the skin since the last build (relative_displacement.hpp).
#include <cstdint>
#include <vector>

#include "core/cancellation.hpp"
#include "core/scratch_vector.hpp"
#include "sph/fluid_particles.hpp"

namespace rupture::sph {

class NeighbourList {
public:
  /// Entries after the last list, all 0 (a valid index): loops may read up to this far past a list.
  static constexpr int kListPadding = 32;

  /// Builds the lists of every particle within `cutoff` (m). dimension 2 ignores z.
  /// Polls `cancel` for every cell scanned (a build of millions of particles takes over a second):
  /// when it is set, returns at once with the lists unusable (the caller must not read them).
  void build(const FluidParticles& p, int dimension, double cutoff, const Cancellation& cancel = {});

  /// A permutation that puts particles in cell order (z-, then y-, then x-major cells of edge
  /// `cellSize`), so that neighbours are close in memory: FluidParticles::permute(order). Valid
  /// until the next build or cellOrder.
  const std::vector<std::int32_t>& cellOrder(const FluidParticles& p, int dimension, double cellSize);

  const std::int32_t* neighbours(std::size_t i) const { return m_start[i]; }
  int count(std::size_t i) const { return m_count[i]; }
  int fluidCount(std::size_t i) const { return m_fluidCount[i]; }
  /// A boundary particle with fluid in reach (a non-empty list): the only ones whose pressure the
  /// fluid sets. Its list's place and length beside its index, so that the wall pass reads one
  /// array in sequence rather than three at scattered places.
  struct WetBoundary {
    std::int32_t particle = 0, count = 0;
    const std::int32_t* neighbours = nullptr;
  };
  /// The wet boundary particles, in index order.
  const std::vector<WetBoundary>& wetBoundary() const { return m_wetBoundary; }
  /// A contiguous range of particles [begin, end) of the pair loop, and the range [lo, hi] of
  /// particles its pairs touch (the particles and their listed neighbours).
  struct Chunk {
    std::size_t begin = 0, end = 0, lo = 0, hi = 0;
    std::size_t touched() const { return end > begin ? hi - lo + 1 : 0; }
  };
  /// The pair loop's work split into chunks, of pair counts tapering from first to last (chunk c
  /// of C gets a share proportional to 2C − c): the threads take them in turn (dynamic), and the
  /// small last ones even out where they finish (W3 on two threads: 0.5 s of 8.4 waited at the
  /// loop's end with equal chunks, 0.17 s with these). How many depends on the particle count only
  /// (never on the thread count), so the sums come out the same for any number of threads.
  const std::vector<Chunk>& chunks() const { return m_chunks; }

  std::size_t totalPairs() const;  ///< directed interacting pairs listed (twice the pairs in fluid lists)
  double cutoff() const { return m_cutoff; }

private:
  std::size_t m_stride = 0;  // list capacity per particle in the search
  double m_cutoff = 0;
  // The lists as the search writes them: each thread's, back to back in the order it scanned the
  // cells (blocks of 64 cells in cell order, which is the particles' order after a re-sort), the
  // fluid particles' and the boundary particles' in two buffers, each padded at the end. So the
  // pair loop reads its lists as a sequential stream (~10 MB on W3, not one line per particle of a
  // fixed-stride table, which its time waited on), the wall extrapolation reads only the walls',
  // and nothing is copied after the search (a list goes once from the cell's scratch, in L1, to its
  // buffer). The buffers live from build to build (no allocation once they have grown).
  struct ThreadLists {
    ScratchVector<std::int32_t> fluid, walls;  // grown by doubling; every entry written before read
    std::size_t fluidUsed = 0, wallsUsed = 0;
  };
  struct Where {
    std::int32_t thread = 0;
    std::size_t offset = 0;
  };
  std::vector<ThreadLists> m_threadLists;
  std::vector<Where> m_where;                  // particle i's list: its thread's buffer, offset
  std::vector<const std::int32_t*> m_start;    // particle i's list
  std::vector<std::int32_t> m_count, m_fluidCount;
  std::vector<WetBoundary> m_wetBoundary;
  std::vector<char> m_isFluid;
  std::vector<Chunk> m_chunks;

  void splitIntoChunks();
  std::vector<std::int32_t> m_cellStart, m_sorted, m_fluidBefore, m_cell, m_cursor;
  std::vector<double> m_sx, m_sy, m_sz;
  std::vector<char> m_sFluid;
};

}  // namespace rupture::sph
