#include "fsi/shell_node_grid.hpp"

#include <algorithm>
#include <cmath>

namespace rupture::fsi {

void ShellNodeGrid::build(const SphShell& shell, double cellSize) {
  const auto& x = shell.positions();
  std::vector<std::int32_t> intact;
  for (std::size_t i = 0; i < shell.size(); ++i)
    if (!shell.fractured(i)) intact.push_back(static_cast<std::int32_t>(i));
  m_sorted.clear();
  m_start.assign(2, 0);
  m_dims[0] = m_dims[1] = m_dims[2] = 1;
  if (intact.empty()) return;
  for (int a = 0; a < 3; ++a) {
    m_lo[a] = m_hi[a] = x[intact[0]][a];
    for (std::int32_t i : intact) {
      m_lo[a] = std::min(m_lo[a], x[i][a]);
      m_hi[a] = std::max(m_hi[a], x[i][a]);
    }
  }
  m_cell = cellSize;
  m_inverse = 1.0 / cellSize;
  for (int a = 0; a < 3; ++a) {
    m_origin[a] = m_lo[a] - cellSize;  // one empty cell on each side: queries clamp into it
    m_dims[a] = static_cast<int>(std::floor((m_hi[a] - m_origin[a]) * m_inverse)) + 2;
  }
  const std::size_t cells = static_cast<std::size_t>(m_dims[0]) * m_dims[1] * m_dims[2];
  m_start.assign(cells + 1, 0);
  std::vector<std::size_t> cellOf(intact.size());
  for (std::size_t s = 0; s < intact.size(); ++s) {
    const auto& p = x[intact[s]];
    cellOf[s] = (static_cast<std::size_t>(coord(p[2], 2)) * m_dims[1] + coord(p[1], 1)) * m_dims[0] + coord(p[0], 0);
    ++m_start[cellOf[s] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) m_start[c + 1] += m_start[c];
  m_sorted.resize(intact.size());
  std::vector<std::int32_t> fill(m_start.begin(), m_start.end() - 1);
  for (std::size_t s = 0; s < intact.size(); ++s) m_sorted[fill[cellOf[s]]++] = intact[s];
}

bool ShellNodeGrid::near(double x, double y, double z) const {
  if (m_sorted.empty()) return false;
  const double v[3] = {x, y, z};
  for (int a = 0; a < 3; ++a)
    if (v[a] < m_lo[a] - m_cell || v[a] > m_hi[a] + m_cell) return false;
  return true;
}

}  // namespace rupture::fsi
