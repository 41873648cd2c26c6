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

/// Particles of one cell and kind scanned together (at most kBatch).
constexpr int kBatch = 8;

/// A batch's particles: index, position, and the neighbours found so far (fluid and boundary
/// ones apart; counted on past the room, which then only counts).
struct BatchScan {
  int k = 0;
  std::int32_t index[kBatch];
  double x[kBatch], y[kBatch], z[kBatch];
  std::int32_t* fluidOut[kBatch];
  std::int32_t* wallOut[kBatch];
  int nf[kBatch], nb[kBatch];
};

/// Which candidates a particle lists (each pair once):
///   Forward: cells after its own in cell order: fluid and boundary particles;
///   Centre:  its own cell: fluid of higher index, and boundary particles;
///   Backward: cells before its own: boundary particles only (their pairs with fluid ones are
///             listed by those, in their Forward cells);
///   FluidOnly: a boundary particle's list, all its fluid neighbours.
enum class ScanMode { Forward, Centre, Backward, FluidOnly };

/// The candidates in sorted order (positions, kinds, indices) and the test against a batch.
struct CandidateRows {
  const double* __restrict sx;
  const double* __restrict sy;
  const double* __restrict sz;
  const char* __restrict sFluid;
  const std::int32_t* __restrict sorted;
  double cut2;
  int stride;  // list capacity: entries past it are counted, not written

  /// Appends the candidates of sorted positions [s0, s1) within the cutoff to each particle of the
  /// batch, by the mode's rule. Both versions list the same neighbours in the same (scan) order.
  template <ScanMode M>
  void scan(BatchScan& b, std::int32_t s0, std::int32_t s1) const {
#ifdef RUPTURE_SPH_AVX512_SCAN
    // 8 candidates at a time, loaded once for the batch: the distance test and the mode's kind
    // test as masks, the accepted indices compressed into the lists; no branch per candidate, nor
    // on whether any is near (a store of nothing costs less than the mispredictions: 29 -> 28 ms).
    const __m512d vcut2 = _mm512_set1_pd(cut2);
    for (std::int32_t s = s0; s < s1; s += kScanWidth) {
      const __mmask8 live = s1 - s >= kScanWidth ? static_cast<__mmask8>(0xFF)
                                                 : static_cast<__mmask8>((1u << (s1 - s)) - 1u);
      const __m512d cx = _mm512_maskz_loadu_pd(live, sx + s);
      const __m512d cy = _mm512_maskz_loadu_pd(live, sy + s);
      const __m512d cz = _mm512_maskz_loadu_pd(live, sz + s);
      const __m128i kinds = _mm_maskz_loadu_epi8(live, sFluid + s);
      const __mmask8 fluid = static_cast<__mmask8>(_mm_test_epi8_mask(kinds, kinds));
      const __m256i ids = _mm256_maskz_loadu_epi32(live, sorted + s);
      for (int q = 0; q < b.k; ++q) {
        const __m512d dx = _mm512_sub_pd(_mm512_set1_pd(b.x[q]), cx);
        const __m512d dy = _mm512_sub_pd(_mm512_set1_pd(b.y[q]), cy);
        const __m512d dz = _mm512_sub_pd(_mm512_set1_pd(b.z[q]), cz);
        const __m512d r2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx)));
        const __mmask8 near = _mm512_mask_cmp_pd_mask(live, r2, vcut2, _CMP_LT_OQ);
        __mmask8 takeFluid = 0, takeWall = 0;
        if constexpr (M == ScanMode::Forward) {
          takeFluid = near & fluid;
          takeWall = near & static_cast<__mmask8>(~fluid);
        } else if constexpr (M == ScanMode::Centre) {
          takeFluid = near & fluid & _mm256_cmpgt_epi32_mask(ids, _mm256_set1_epi32(b.index[q]));
          takeWall = near & static_cast<__mmask8>(~fluid);
        } else if constexpr (M == ScanMode::Backward) {
          takeWall = near & static_cast<__mmask8>(~fluid);
        } else {
          takeFluid = near & fluid;
        }
        int& nf = b.nf[q];
        int& nb = b.nb[q];
        if (nf + nb <= stride) {  // room for 8 more in either (room: stride + 8)
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(b.fluidOut[q] + nf), _mm256_maskz_compress_epi32(takeFluid, ids));
          _mm256_storeu_si256(reinterpret_cast<__m256i*>(b.wallOut[q] + nb), _mm256_maskz_compress_epi32(takeWall, ids));
        }
        nf += __builtin_popcount(takeFluid);
        nb += __builtin_popcount(takeWall);
      }
    }
#else
    for (int q = 0; q < b.k; ++q) {
      int& nf = b.nf[q];
      int& nb = b.nb[q];
      for (std::int32_t s = s0; s < s1; ++s) {
        const std::int32_t j = sorted[s];
        const bool fluidJ = sFluid[s];
        if constexpr (M == ScanMode::Centre) {
          if (fluidJ && j <= b.index[q]) continue;
        } else if constexpr (M == ScanMode::Backward) {
          if (fluidJ) continue;
        } else if constexpr (M == ScanMode::FluidOnly) {
          if (!fluidJ) continue;
        }
        const double dx = b.x[q] - sx[s], dy = b.y[q] - sy[s], dz = b.z[q] - sz[s];
        if (dx * dx + dy * dy + dz * dz >= cut2) continue;
        if (fluidJ) {
          if (nf + nb < stride) b.fluidOut[q][nf] = j;
          ++nf;
        } else {
          if (nf + nb < stride) b.wallOut[q][nb] = j;
          ++nb;
        }
      }
    }
#endif
  }
};

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

void NeighbourList::build(const FluidParticles& p, int dimension, double cutoff, const Cancellation& cancel) {
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
    const std::int32_t* __restrict sorted = m_sorted.data();
    const std::int32_t* __restrict cellStart = m_cellStart.data();
    const std::int32_t* __restrict fluidBefore = m_fluidBefore.data();
    const char* __restrict sFluid = m_sFluid.data();
    const double* __restrict sx = m_sx.data();
    const double* __restrict sy = m_sy.data();
    const double* __restrict sz = m_sz.data();
    const int stride = static_cast<int>(m_stride);
    const std::size_t cells = g.count();
#pragma omp parallel num_threads(threads) reduction(max : overflow) if (threads > 1)
    {
      // Each thread appends the lists of the particles it scans to its own two buffers (fluid
      // particles' lists, boundary particles' lists): written once, where the pair loops read them.
      ThreadLists& mine = m_threadLists[omp_get_thread_num()];
      mine.fluidUsed = mine.wallsUsed = 0;
      // The particles of one cell and kind are scanned together (a batch): they share the rows of
      // candidates, which are loaded once for all of them. Each collects its fluid and boundary
      // neighbours here (room entries each), then its list is copied to the buffer.
      std::vector<std::int32_t> scratch(2 * kBatch * room);
      // Dynamic: a dry wall particle (no fluid in reach) costs next to nothing and a fluid one a full
      // scan, and in cell order they are not spread evenly; a particle's list is the same whichever
      // thread scans it, and the pair loops find it by pointer (m_start).
#pragma omp for schedule(dynamic, 64)
      for (std::size_t c = 0; c < cells; ++c) {
        const std::int32_t first = cellStart[c], last = cellStart[c + 1];
        if (first == last || cancel.requested()) continue;
        const int cx = static_cast<int>(c % g.dims[0]), cy = static_cast<int>(c / g.dims[0] % g.dims[1]);
        const int cz = static_cast<int>(c / (static_cast<std::size_t>(g.dims[0]) * g.dims[1]));
        const int x0 = std::max(cx - 2, 0), x1 = std::min(cx + 2, g.dims[0] - 1);
        for (const bool fluidBatch : {true, false}) {
          for (std::int32_t from = first; from < last;) {
            // The next batch: up to kBatch particles of this kind, by sorted position.
            std::int32_t members[kBatch];
            int k = 0;
            for (; from < last && k < kBatch; ++from)
              if ((sFluid[from] != 0) == fluidBatch) members[k++] = from;
            if (k == 0) break;
            BatchScan batch;
            batch.k = k;
            for (int q = 0; q < k; ++q) {
              const std::int32_t m = members[q];
              batch.index[q] = sorted[m];
              batch.x[q] = sx[m];
              batch.y[q] = sy[m];
              batch.z[q] = sz[m];
              batch.fluidOut[q] = scratch.data() + (2 * q) * room;
              batch.wallOut[q] = scratch.data() + (2 * q + 1) * room;
              batch.nf[q] = batch.nb[q] = 0;
            }
            const CandidateRows rows{sx, sy, sz, sFluid, sorted, cut2, stride};
            auto fluidIn = [&](std::int32_t s0, std::int32_t s1) { return fluidBefore[s1] - fluidBefore[s0]; };
            for (int za = std::max(cz - 2, 0); za <= std::min(cz + 2, g.dims[2] - 1); ++za)
              for (int yb = std::max(cy - 2, 0); yb <= std::min(cy + 2, g.dims[1] - 1); ++yb) {
                const std::size_t row = (static_cast<std::size_t>(za) * g.dims[1] + yb) * g.dims[0];
                // Cells x0..x1 of one row are contiguous in the sorted order.
                const std::int32_t s0 = cellStart[row + x0], s1 = cellStart[row + x1 + 1];
                if (!fluidBatch) {
                  if (fluidIn(s0, s1) > 0) rows.scan<ScanMode::FluidOnly>(batch, s0, s1);
                  continue;
                }
                const int order = za != cz ? za - cz : yb - cy;  // rows after (> 0) or before (< 0) its own
                if (order > 0) {
                  rows.scan<ScanMode::Forward>(batch, s0, s1);
                } else if (order < 0) {
                  if (fluidIn(s0, s1) < s1 - s0) rows.scan<ScanMode::Backward>(batch, s0, s1);
                } else {
                  if (fluidIn(s0, first) < first - s0) rows.scan<ScanMode::Backward>(batch, s0, first);
                  rows.scan<ScanMode::Centre>(batch, first, last);
                  rows.scan<ScanMode::Forward>(batch, last, s1);
                }
              }
            ScratchVector<std::int32_t>& buffer = fluidBatch ? mine.fluid : mine.walls;
            std::size_t& used = fluidBatch ? mine.fluidUsed : mine.wallsUsed;
            for (int q = 0; q < k; ++q) {
              const int nf = batch.nf[q], nb = batch.nb[q], total = nf + nb;
              if (total > stride) {
                overflow = std::max(overflow, total);
                continue;
              }
              // Room for this list and the padding; grown (rarely: the buffers live from build to
              // build) by doubling.
              if (buffer.size() < used + total + kListPadding)
                buffer.resize(std::max(2 * buffer.size(), used + total + kListPadding));
              std::int32_t* out = buffer.data() + used;
              std::copy(batch.fluidOut[q], batch.fluidOut[q] + nf, out);
              std::copy(batch.wallOut[q], batch.wallOut[q] + nb, out + nf);
              const std::int32_t i = batch.index[q];
              m_count[i] = total;
              m_fluidCount[i] = nf;
              m_where[i] = {static_cast<std::int32_t>(omp_get_thread_num()), used};
              used += static_cast<std::size_t>(total);
            }
          }
        }
      }
      // Padded with particle 0: the pair loops load and prefetch up to kListPadding entries past a
      // list, which are the next list's in the buffer or these.
      for (auto [buffer, used] : {std::pair{&mine.fluid, mine.fluidUsed}, std::pair{&mine.walls, mine.wallsUsed}}) {
        if (buffer->size() < used + kListPadding) buffer->resize(used + kListPadding);
        std::fill_n(buffer->data() + used, kListPadding, 0);
      }
    }
    if (cancel.requested()) return;  // half scanned: unusable, and the caller knows
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
  m_wetBoundary.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (!m_isFluid[i] && m_count[i] > 0) m_wetBoundary.push_back({static_cast<std::int32_t>(i), m_count[i], m_start[i]});
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
