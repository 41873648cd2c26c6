#pragma once
// Uniform-grid binning of particle centres (counting sort), for neighbour searches in O(N).
#include <cstdint>
#include <vector>

#include "core/particle_store.hpp"

namespace rupture {

class CellList {
public:
  /// Bins every particle into cubic cells of edge >= cellSize over the particles' bounding box.
  void build(const ParticleStore& p, double cellSize);

  /// Calls visit(k) for every particle k in the cells around point (x, y, z), itself included.
  template <class Visit>
  void forEachNear(double x, double y, double z, Visit&& visit) const {
    const int cx = cellCoord(x, 0), cy = cellCoord(y, 1), cz = cellCoord(z, 2);
    for (int a = cz - 1; a <= cz + 1; ++a) {
      if (a < 0 || a >= m_dims[2]) continue;
      for (int b = cy - 1; b <= cy + 1; ++b) {
        if (b < 0 || b >= m_dims[1]) continue;
        for (int c = cx - 1; c <= cx + 1; ++c) {
          if (c < 0 || c >= m_dims[0]) continue;
          const std::size_t cell = (static_cast<std::size_t>(a) * m_dims[1] + b) * m_dims[0] + c;
          for (std::int32_t s = m_start[cell]; s < m_start[cell + 1]; ++s) visit(m_sorted[s]);
        }
      }
    }
  }

  /// Calls visit(k) for every particle k in the cells overlapping the box [lo, hi] (a superset of
  /// the particles inside it: the caller tests the exact distance).
  template <class Visit>
  void forEachInBox(const double lo[3], const double hi[3], Visit&& visit) const {
    for (int a = cellCoord(lo[2], 2); a <= cellCoord(hi[2], 2); ++a)
      for (int b = cellCoord(lo[1], 1); b <= cellCoord(hi[1], 1); ++b)
        for (int c = cellCoord(lo[0], 0); c <= cellCoord(hi[0], 0); ++c) {
          const std::size_t cell = (static_cast<std::size_t>(a) * m_dims[1] + b) * m_dims[0] + c;
          for (std::int32_t s = m_start[cell]; s < m_start[cell + 1]; ++s) visit(m_sorted[s]);
        }
  }

private:
  int cellCoord(double v, int axis) const {
    int c = static_cast<int>((v - m_origin[axis]) * m_inverseSize);
    return c < 0 ? 0 : (c >= m_dims[axis] ? m_dims[axis] - 1 : c);
  }
  double m_origin[3] = {0, 0, 0};
  double m_inverseSize = 1;
  int m_dims[3] = {1, 1, 1};
  std::vector<std::int32_t> m_start, m_sorted;
};

}  // namespace rupture
