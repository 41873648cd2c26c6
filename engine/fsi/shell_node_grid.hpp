#pragma once
// A uniform cell grid over the intact nodes of a shell, for the fluid–shell contact search:
// each fluid particle near the plate visits the 27 cells around it, O(N + M) per step instead
// of O(N·M). Fractured nodes are left out: they carry no pinball, so cracks let water through.
#include <cstdint>
#include <vector>

#include "shell/sph_shell.hpp"

namespace rupture::fsi {

class ShellNodeGrid {
public:
  /// Bins the intact nodes of `shell` in cells of edge `cellSize` (m).
  void build(const SphShell& shell, double cellSize);

  /// False when (x, y, z) is farther than one cell from every node's bounding box: no contact.
  bool near(double x, double y, double z) const;

  /// Calls visit(node) for every intact node in the 27 cells around (x, y, z).
  template <class Visit>
  void forEachNear(double x, double y, double z, Visit&& visit) const {
    const int c[3] = {coord(x, 0), coord(y, 1), coord(z, 2)};
    for (int k = std::max(0, c[2] - 1); k <= std::min(m_dims[2] - 1, c[2] + 1); ++k)
      for (int j = std::max(0, c[1] - 1); j <= std::min(m_dims[1] - 1, c[1] + 1); ++j)
        for (int i = std::max(0, c[0] - 1); i <= std::min(m_dims[0] - 1, c[0] + 1); ++i) {
          const std::size_t cell = (static_cast<std::size_t>(k) * m_dims[1] + j) * m_dims[0] + i;
          for (std::int32_t s = m_start[cell]; s < m_start[cell + 1]; ++s) visit(static_cast<std::size_t>(m_sorted[s]));
        }
  }

  bool empty() const { return m_sorted.empty(); }

private:
  int coord(double v, int a) const {
    const int c = static_cast<int>(std::floor((v - m_origin[a]) * m_inverse));
    return c < 0 ? 0 : (c >= m_dims[a] ? m_dims[a] - 1 : c);
  }

  double m_origin[3] = {0, 0, 0}, m_lo[3] = {0, 0, 0}, m_hi[3] = {0, 0, 0};
  double m_inverse = 1, m_cell = 1;
  int m_dims[3] = {1, 1, 1};
  std::vector<std::int32_t> m_start, m_sorted;
};

}  // namespace rupture::fsi
