#include "sph/relative_displacement.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace rupture::sph {

namespace {

/// Squared diagonal of the box spanning two non-empty boxes.
template <class Box>
double unionDiagonal2(const Box& a, const Box& b, int dimension) {
  double d2 = 0;
  for (int k = 0; k < dimension; ++k) {
    const double e = std::max(a.hi[k], b.hi[k]) - std::min(a.lo[k], b.lo[k]);
    d2 += e * e;
  }
  return d2;
}

}  // namespace

void RelativeDisplacementBound::reset(const FluidParticles& p, int dimension, double reach,
                                      const std::vector<char>& bodyMoves) {
  m_dimension = dimension;
  const std::size_t n = p.size();
  // At most one cell per particle: each thread keeps two boxes (48 bytes each) a cell, so a
  // scattered cloud must not multiply the memory (a dense fluid has about 20 particles in a cell
  // of the cutoff in 3D, 8 in 2D).
  m_grid = CellGrid(p, dimension, reach, 1.0);
  m_threadBoxes.clear();  // evaluate sizes it for its thread count, all boxes empty
  m_merged.resize(2 * m_grid.count());
  m_fixedIn.assign(m_grid.count(), 0);
  m_movers.clear();
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t b = p.body[k];
    if (b == kFluid || bodyMoves.at(static_cast<std::size_t>(b))) m_movers.push_back(static_cast<std::int32_t>(k));
    else m_fixedIn[m_grid.cellOf(p, k)] = 1;
  }
}

double RelativeDisplacementBound::evaluate(const FluidParticles& p, std::span<const double> x0,
                                           std::span<const double> y0, std::span<const double> z0) {
  const std::size_t cells = m_grid.count(), movers = m_movers.size();
  const int dimension = m_dimension;
  const int threads = worthParallel(movers) ? omp_get_max_threads() : 1;
  if (m_threadBoxes.size() < static_cast<std::size_t>(threads) * 2 * cells)
    m_threadBoxes.resize(static_cast<std::size_t>(threads) * 2 * cells);  // new boxes are empty

  // 1. Each thread widens its own cells' boxes with its movers' displacements. Neighbours in index
  //    order mostly share a cell (particles are kept in cell order), so a run of them is gathered
  //    in a local box and written once.
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    Box* mine = m_threadBoxes.data() + static_cast<std::size_t>(omp_get_thread_num()) * 2 * cells;
    std::size_t slot = 0;
    Box run;
    auto flush = [&] {
      if (run.empty()) return;
      mine[slot].widen(run);
      run = Box{};
    };
#pragma omp for schedule(static)
    for (std::size_t q = 0; q < movers; ++q) {
      const std::int32_t k = m_movers[q];
      const std::size_t s = 2 * m_grid.cellOf(p, k) + (p.body[k] == kFluid ? 0 : 1);
      if (s != slot) {
        flush();
        slot = s;
      }
      const double d[3] = {p.x[k] - x0[k], p.y[k] - y0[k], dimension == 3 ? p.z[k] - z0[k] : 0.0};
      run.widen(d, d);
    }
    flush();
  }
  // 2. The threads' boxes merged per cell, and emptied for the next call. A fixed body's members
  //    sit at displacement 0.
#pragma omp parallel for schedule(static) if (threads > 1) num_threads(threads)
  for (std::size_t c = 0; c < 2 * cells; ++c) {
    Box merged;
    constexpr double kOrigin[3] = {0, 0, 0};
    if (c % 2 == 1 && m_fixedIn[c / 2]) merged.widen(kOrigin, kOrigin);
    for (int t = 0; t < threads; ++t) {
      Box& b = m_threadBoxes[static_cast<std::size_t>(t) * 2 * cells + c];
      merged.widen(b);
      b = Box{};
    }
    m_merged[c] = merged;
  }
  // 3. Over every cell with fluid: its fluid box against the fluid and the boundary box of itself
  //    and of each adjacent cell.
  const int reach[3] = {1, 1, dimension == 3 ? 1 : 0};
  double worst2 = 0;
#pragma omp parallel for schedule(static) reduction(max : worst2) if (threads > 1) num_threads(threads)
  for (std::size_t c = 0; c < cells; ++c) {
    const Box& fluid = m_merged[2 * c];
    if (fluid.empty()) continue;
    const int cx = static_cast<int>(c % m_grid.dims[0]), cy = static_cast<int>(c / m_grid.dims[0] % m_grid.dims[1]),
              cz = static_cast<int>(c / (static_cast<std::size_t>(m_grid.dims[0]) * m_grid.dims[1]));
    for (int z = std::max(cz - reach[2], 0); z <= std::min(cz + reach[2], m_grid.dims[2] - 1); ++z)
      for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, m_grid.dims[1] - 1); ++y)
        for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, m_grid.dims[0] - 1); ++x) {
          const std::size_t other = (static_cast<std::size_t>(z) * m_grid.dims[1] + y) * m_grid.dims[0] + x;
          for (int kind = 0; kind < 2; ++kind) {
            const Box& b = m_merged[2 * other + kind];
            if (!b.empty()) worst2 = std::max(worst2, unionDiagonal2(fluid, b, dimension));
          }
        }
  }
  return std::sqrt(worst2);
}

}  // namespace rupture::sph
