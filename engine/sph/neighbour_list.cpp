#include "sph/neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <omp.h>

#include "core/parallel.hpp"
#include "sph/cell_grid.hpp"

#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__) && !defined(RUPTURE_SPH_NO_INTRINSICS)
#include <immintrin.h>
#define RUPTURE_SPH_AVX512_SCAN 1
#endif

namespace rupture::sph {

namespace {

/// Candidates the list search tests at a time (one AVX-512 vector of doubles).
constexpr int kScanWidth = 8;

/// Counting sort of particles by cell: start (cells + 1) and the particles in cell order. cell and
/// cursor are scratch, kept by the caller so that a rebuild allocates (and page-faults) nothing.
void binParticles(const FluidParticles& p, const CellGrid& g, std::vector<std::int32_t>& start,
                  std::vector<std::int32_t>& sorted, std::vector<std::int32_t>& cell,
                  std::vector<std::int32_t>& cursor) {
  const std::size_t n = p.size();
  start.assign(g.count() + 1, 0);
  cell.resize(n);
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t k = 0; k < n; ++k) cell[k] = static_cast<std::int32_t>(g.cellOf(p, k));
  for (std::size_t k = 0; k < n; ++k) ++start[cell[k] + 1];
  for (std::size_t c = 0; c < g.count(); ++c) start[c + 1] += start[c];
  sorted.resize(n);
  cursor.assign(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < n; ++k) sorted[cursor[cell[k]]++] = static_cast<std::int32_t>(k);
}

}  // namespace

const std::vector<std::int32_t>& NeighbourList::cellOrder(const FluidParticles& p, int dimension, double cellSize) {
  // The search's scratch (build overwrites it): a re-sort allocates, and page-faults, nothing.
  const CellGrid g(p, dimension, cellSize, 8.0);
  binParticles(p, g, m_cellStart, m_sorted, m_cell, m_cursor);
  return m_sorted;
}

std::size_t NeighbourList::totalPairs() const {
  // Each interacting pair sits once in a fluid particle's list; a wall's list repeats its fluid–wall pairs.
  std::size_t total = 0;
  for (std::size_t i = 0; i < m_count.size(); ++i)
    if (m_isFluid[i]) total += static_cast<std::size_t>(m_count[i]);
  return 2 * total;
}

void NeighbourList::build(const FluidParticles& p, int dimension, double cutoff) {
  const std::size_t n = p.size();
  m_cutoff = cutoff;
  // Cells of half the cutoff and a ±2 stencil: 125 (3D) half-size cells hold about half the
  // candidates of 27 full-size ones.
  const CellGrid g(p, dimension, 0.5 * cutoff, 8.0);
  binParticles(p, g, m_cellStart, m_sorted, m_cell, m_cursor);
  m_count.assign(n, 0);
  m_fluidCount.assign(n, 0);
  m_isFluid.resize(n);
  for (std::size_t i = 0; i < n; ++i) m_isFluid[i] = p.body[i] == kFluid;
  if (m_stride == 0) {
    // Neighbours of a particle in the bulk of a lattice of spacing ~ cutoff/2.6, with room to spare.
    const double ratio = 2.6 * 1.1;
    m_stride = static_cast<std::size_t>(dimension == 3 ? 4.0 / 3.0 * std::numbers::pi * ratio * ratio * ratio
                                                       : std::numbers::pi * ratio * ratio) + 24;
  }
  const double cut2 = cutoff * cutoff;
  const bool is3d = dimension == 3;
  // Positions and kinds in cell order, so that the candidate scan reads memory in sequence; and the
  // number of fluid particles before each sorted position, so that a boundary particle skips the
  // rows of cells that hold no fluid (it lists fluid only).
  m_sx.resize(n);
  m_sy.resize(n);
  m_sz.resize(n);
  m_sFluid.resize(n);
  m_fluidBefore.resize(n + 1);
  m_fluidBefore[0] = 0;
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t s = 0; s < n; ++s) {
    const std::int32_t j = m_sorted[s];
    m_sx[s] = p.x[j];
    m_sy[s] = p.y[j];
    m_sz[s] = is3d ? p.z[j] : 0.0;
    m_sFluid[s] = p.body[j] == kFluid;
  }
  for (std::size_t s = 0; s < n; ++s) m_fluidBefore[s + 1] = m_fluidBefore[s] + m_sFluid[s];
  const int threads = worthParallel(n) ? std::max(1, omp_get_max_threads()) : 1;
  if (m_threadLists.size() < static_cast<std::size_t>(threads)) m_threadLists.resize(threads);
  m_where.resize(n);
  while (true) {
    // Room for m_stride entries and one vector store past them (the scan writes 8 at a time).
    const std::size_t room = m_stride + kScanWidth;
    int overflow = 0;
#pragma omp parallel num_threads(threads) reduction(max : overflow) if (threads > 1)
    {
      // Each thread appends the lists of the particles it scans to its own two buffers (fluid
      // particles' lists, boundary particles' lists): written once, where the pair loops read them.
      ThreadLists& mine = m_threadLists[omp_get_thread_num()];
      mine.fluidUsed = mine.wallsUsed = 0;
      // Boundary neighbours are collected here and moved behind the fluid ones.
      std::vector<std::int32_t> wallScratch(room);
      // Dynamic: a dry wall particle (no fluid in reach) costs next to nothing and a fluid one a full
      // scan, and in cell order they are not spread evenly; a particle's list is the same whichever
      // thread scans it, and the pair loops find it by pointer (m_start).
#pragma omp for schedule(dynamic, 512)
      for (std::size_t i = 0; i < n; ++i) {
        const double xi = p.x[i], yi = p.y[i], zi = is3d ? p.z[i] : 0.0;
        const bool fluidI = p.body[i] == kFluid;
        const int cx = g.coord(xi, 0), cy = g.coord(yi, 1), cz = g.coord(p.z[i], 2);
        std::vector<std::int32_t>& buffer = fluidI ? mine.fluid : mine.walls;
        std::size_t& used = fluidI ? mine.fluidUsed : mine.wallsUsed;
        // Room for this list and the padding; grown (rarely: the buffers live from build to build)
        // by doubling.
        if (buffer.size() < used + room + kListPadding) buffer.resize(std::max(2 * buffer.size(), used + room + kListPadding));
        std::int32_t* out = buffer.data() + used;
        std::int32_t* walls = wallScratch.data();
        const int stride = static_cast<int>(m_stride);
        int nf = 0, nb = 0;
        const int x0 = std::max(cx - 2, 0), x1 = std::min(cx + 2, g.dims[0] - 1);
        // Candidates of sorted positions [s0, s1). Which ones a particle lists (each pair once):
        //   Forward: cells after its own in cell order: fluid and boundary particles;
        //   Centre:  its own cell: fluid of higher index, and boundary particles;
        //   Backward: cells before its own: boundary particles only (their pairs with fluid ones
        //             are listed by those, in their Forward cells);
        //   FluidOnly: a boundary particle's list, all its fluid neighbours.
        // Both versions list the same neighbours in the same (scan) order.
        enum Mode { Forward, Centre, Backward, FluidOnly };
        auto scan = [&]<int M>(std::int32_t s0, std::int32_t s1) {
#ifdef RUPTURE_SPH_AVX512_SCAN
          // 8 candidates at a time: the distance test and the mode's kind test as masks, the
          // accepted indices compressed into the list (no branch per candidate).
          const __m512d vx = _mm512_set1_pd(xi), vy = _mm512_set1_pd(yi), vz = _mm512_set1_pd(zi);
          const __m512d vcut2 = _mm512_set1_pd(cut2);
          const __m256i vi = _mm256_set1_epi32(static_cast<std::int32_t>(i));
          for (std::int32_t s = s0; s < s1; s += kScanWidth) {
            const __mmask8 live = s1 - s >= kScanWidth ? static_cast<__mmask8>(0xFF)
                                                       : static_cast<__mmask8>((1u << (s1 - s)) - 1u);
            const __m512d dx = _mm512_sub_pd(vx, _mm512_maskz_loadu_pd(live, m_sx.data() + s));
            const __m512d dy = _mm512_sub_pd(vy, _mm512_maskz_loadu_pd(live, m_sy.data() + s));
            const __m512d dz = _mm512_sub_pd(vz, _mm512_maskz_loadu_pd(live, m_sz.data() + s));
            const __m512d r2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx)));
            const __mmask8 near = _mm512_mask_cmp_pd_mask(live, r2, vcut2, _CMP_LT_OQ);
            if (near == 0) continue;
            const __m128i kinds = _mm_maskz_loadu_epi8(live, m_sFluid.data() + s);
            const __mmask8 fluid = static_cast<__mmask8>(_mm_test_epi8_mask(kinds, kinds));
            const __m256i ids = _mm256_maskz_loadu_epi32(live, m_sorted.data() + s);
            __mmask8 takeFluid = 0, takeWall = 0;
            if constexpr (M == Forward) {
              takeFluid = near & fluid;
              takeWall = near & static_cast<__mmask8>(~fluid);
            } else if constexpr (M == Centre) {
              takeFluid = near & fluid & _mm256_cmpgt_epi32_mask(ids, vi);
              takeWall = near & static_cast<__mmask8>(~fluid);
            } else if constexpr (M == Backward) {
              takeWall = near & static_cast<__mmask8>(~fluid);
            } else {
              takeFluid = near & fluid;
            }
            if (nf + nb <= stride) {  // room for 8 more in either (slot and scratch: stride + 8)
              _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + nf), _mm256_maskz_compress_epi32(takeFluid, ids));
              _mm256_storeu_si256(reinterpret_cast<__m256i*>(walls + nb), _mm256_maskz_compress_epi32(takeWall, ids));
            }
            nf += __builtin_popcount(takeFluid);
            nb += __builtin_popcount(takeWall);
          }
#else
          for (std::int32_t s = s0; s < s1; ++s) {
            const std::int32_t j = m_sorted[s];
            const bool fluidJ = m_sFluid[s];
            if constexpr (M == Centre) {
              if (fluidJ && static_cast<std::size_t>(j) <= i) continue;
            } else if constexpr (M == Backward) {
              if (fluidJ) continue;
            } else if constexpr (M == FluidOnly) {
              if (!fluidJ) continue;
            }
            const double dx = xi - m_sx[s], dy = yi - m_sy[s], dz = zi - m_sz[s];
            if (dx * dx + dy * dy + dz * dz >= cut2) continue;
            if (fluidJ) {
              if (nf + nb < stride) out[nf] = j;
              ++nf;
            } else {
              if (nf + nb < stride) walls[nb] = j;
              ++nb;
            }
          }
#endif
        };
        auto fluidIn = [&](std::int32_t s0, std::int32_t s1) { return m_fluidBefore[s1] - m_fluidBefore[s0]; };
        for (int a = std::max(cz - 2, 0); a <= std::min(cz + 2, g.dims[2] - 1); ++a)
          for (int b = std::max(cy - 2, 0); b <= std::min(cy + 2, g.dims[1] - 1); ++b) {
            const std::size_t row = (static_cast<std::size_t>(a) * g.dims[1] + b) * g.dims[0];
            // Cells x0..x1 of one row are contiguous in the sorted order.
            const std::int32_t s0 = m_cellStart[row + x0], s1 = m_cellStart[row + x1 + 1];
            if (!fluidI) {
              if (fluidIn(s0, s1) > 0) scan.template operator()<FluidOnly>(s0, s1);
              continue;
            }
            const int order = a != cz ? a - cz : b - cy;  // rows after (> 0) or before (< 0) its own
            if (order > 0) {
              scan.template operator()<Forward>(s0, s1);
            } else if (order < 0) {
              if (fluidIn(s0, s1) < s1 - s0) scan.template operator()<Backward>(s0, s1);
            } else {
              const std::int32_t c0 = m_cellStart[row + cx], c1 = m_cellStart[row + cx + 1];
              if (fluidIn(s0, c0) < c0 - s0) scan.template operator()<Backward>(s0, c0);
              scan.template operator()<Centre>(c0, c1);
              scan.template operator()<Forward>(c1, s1);
            }
          }
        const int total = nf + nb;
        if (total > stride) {
          overflow = std::max(overflow, total);
          continue;
        }
        std::copy(walls, walls + nb, out + nf);
        m_count[i] = total;
        m_fluidCount[i] = nf;
        m_where[i] = {static_cast<std::int32_t>(omp_get_thread_num()), used};
        used += static_cast<std::size_t>(total);
      }
      // Padded with particle 0: the pair loops load and prefetch up to kListPadding entries past a
      // list, which are the next list's in the buffer or these.
      for (auto [buffer, used] : {std::pair{&mine.fluid, mine.fluidUsed}, std::pair{&mine.walls, mine.wallsUsed}}) {
        if (buffer->size() < used + kListPadding) buffer->resize(used + kListPadding);
        std::fill_n(buffer->data() + used, kListPadding, 0);
      }
    }
    if (overflow == 0) break;
    m_stride = static_cast<std::size_t>(overflow) + overflow / 4 + 8;
  }
  // Where each list lies, now that no buffer grows any more.
  m_start.resize(n);
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t i = 0; i < n; ++i) {
    const ThreadLists& owner = m_threadLists[m_where[i].thread];
    m_start[i] = (m_isFluid[i] ? owner.fluid.data() : owner.walls.data()) + m_where[i].offset;
  }
  splitIntoChunks();
}

void NeighbourList::splitIntoChunks() {
  const std::size_t n = m_count.size();
  // 1, 2, 4 or 8 chunks of at least 4,096 particles on average; no more than 8, as a chunk's buffer
  // spans its particles and their neighbours (on W3 about twice its own), so each more chunk adds
  // memory traffic.
  std::size_t chunks = 1;
  while (chunks < 8 && n / (2 * chunks) >= 4096) chunks *= 2;
  std::size_t work = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (m_isFluid[i]) work += static_cast<std::size_t>(m_count[i]);
  m_chunks.assign(chunks, {});
  std::size_t i = 0, done = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    Chunk& k = m_chunks[c];
    k.begin = i;
    // Shares proportional to 2C − c (chunks(), neighbour_list.hpp): the first c + 1 hold this many of all.
    const std::size_t cumulative = (c + 1) * 2 * chunks - c * (c + 1) / 2, all = chunks * (3 * chunks + 1) / 2;
    const std::size_t target = static_cast<std::size_t>(static_cast<double>(work) * cumulative / all);
    while (i < n && (c + 1 == chunks || done < target)) {
      if (m_isFluid[i]) done += static_cast<std::size_t>(m_count[i]);
      ++i;
    }
    k.end = i;
  }
  // The particles each chunk touches: a scan of its lists, the chunks in parallel.
#pragma omp parallel for schedule(static, 1) if (worthParallel(n))
  for (std::size_t c = 0; c < chunks; ++c) {
    Chunk& k = m_chunks[c];
    std::int32_t lo = static_cast<std::int32_t>(k.begin);
    std::int32_t hi = static_cast<std::int32_t>(k.end > k.begin ? k.end - 1 : k.begin);
    for (std::size_t a = k.begin; a < k.end; ++a) {
      if (!m_isFluid[a]) continue;
      const std::int32_t* nb = neighbours(a);
      for (int m = 0; m < m_count[a]; ++m) {
        lo = std::min(lo, nb[m]);
        hi = std::max(hi, nb[m]);
      }
    }
    k.lo = static_cast<std::size_t>(lo);
    k.hi = static_cast<std::size_t>(hi);
  }
}

}  // namespace rupture::sph
