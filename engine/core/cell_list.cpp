#include "core/cell_list.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {

void CellList::build(const ParticleStore& p, double cellSize) {
  const std::size_t n = p.size();
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  if (n > 0) {
    lo[0] = hi[0] = p.x[0]; lo[1] = hi[1] = p.y[0]; lo[2] = hi[2] = p.z[0];
  }
  for (std::size_t k = 0; k < n; ++k) {
    const double v[3] = {p.x[k], p.y[k], p.z[k]};
    for (int a = 0; a < 3; ++a) { lo[a] = std::min(lo[a], v[a]); hi[a] = std::max(hi[a], v[a]); }
  }
  // Grow the cells if needed so a scattered cloud cannot ask for an absurd number of them.
  double size = cellSize;
  auto cellsFor = [&](double edge) {
    double count = 1;
    for (int a = 0; a < 3; ++a) count *= std::floor((hi[a] - lo[a]) / edge) + 1;
    return count;
  };
  while (cellsFor(size) > 8.0 * static_cast<double>(n) + 64.0) size *= 1.25;
  m_inverseSize = 1.0 / size;
  for (int a = 0; a < 3; ++a) {
    m_origin[a] = lo[a];
    m_dims[a] = static_cast<int>(std::floor((hi[a] - lo[a]) * m_inverseSize)) + 1;
  }
  const std::size_t cellCount = static_cast<std::size_t>(m_dims[0]) * m_dims[1] * m_dims[2];
  m_start.assign(cellCount + 1, 0);
  std::vector<std::int32_t> cellOf(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t cell =
        (static_cast<std::size_t>(cellCoord(p.z[k], 2)) * m_dims[1] + cellCoord(p.y[k], 1)) * m_dims[0] +
        cellCoord(p.x[k], 0);
    cellOf[k] = static_cast<std::int32_t>(cell);
    ++m_start[cell + 1];
  }
  for (std::size_t c = 0; c < cellCount; ++c) m_start[c + 1] += m_start[c];
  m_sorted.assign(n, 0);
  std::vector<std::int32_t> cursor(m_start.begin(), m_start.end() - 1);
  for (std::size_t k = 0; k < n; ++k) m_sorted[cursor[cellOf[k]]++] = static_cast<std::int32_t>(k);
}

}  // namespace rupture
