#include "sph/cell_grid.hpp"

#include <algorithm>
#include <cmath>

namespace rupture::sph {

CellGrid::CellGrid(const FluidParticles& p, int dimension, double minEdge, double cellsPerParticle) {
  const std::size_t n = p.size();
  const ParticleArray<double>* coords[3] = {&p.x, &p.y, &p.z};
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (int a = 0; a < dimension && n > 0; ++a) {
    const auto [mn, mx] = std::minmax_element(coords[a]->begin(), coords[a]->end());
    lo[a] = *mn;
    hi[a] = *mx;
  }
  auto cells = [&](double edge) {
    double c = 1;
    for (int a = 0; a < dimension; ++a) c *= std::floor((hi[a] - lo[a]) / edge) + 1;
    return c;
  };
  double edge = minEdge;
  while (cells(edge) > cellsPerParticle * static_cast<double>(n) + 64.0) edge *= 1.25;
  inverseSize = 1.0 / edge;
  for (int a = 0; a < dimension; ++a) {
    origin[a] = lo[a];
    dims[a] = static_cast<int>(std::floor((hi[a] - lo[a]) * inverseSize)) + 1;
  }
}

}  // namespace rupture::sph
