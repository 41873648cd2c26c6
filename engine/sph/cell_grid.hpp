#pragma once
// A uniform grid of cells over the particles' bounding box, cells numbered x-fastest, for the
// neighbour search (neighbour_list.cpp) and the list's rebuild bound (relative_displacement.cpp).
// A position outside the box falls in the nearest border cell, so two positions closer than an
// edge are in the same or adjacent cells wherever they are.
#include <cstddef>

#include "sph/fluid_particles.hpp"

namespace rupture::sph {

struct CellGrid {
  double origin[3] = {0, 0, 0};
  double inverseSize = 1;  ///< 1/edge (1/m)
  int dims[3] = {1, 1, 1};

  CellGrid() = default;
  /// Cells of edge >= minEdge (m) over the box of p's positions (dimension 2 ignores z). The edge
  /// grows by 1.25 until there are at most cellsPerParticle · n + 64 cells: a scattered cloud (a
  /// splash) must not ask for an absurd number of cells.
  CellGrid(const FluidParticles& p, int dimension, double minEdge, double cellsPerParticle);

  int coord(double v, int a) const {
    const double f = (v - origin[a]) * inverseSize;
    return f <= 0.0 ? 0 : (f >= dims[a] - 1 ? dims[a] - 1 : static_cast<int>(f));
  }
  std::size_t cellOf(double x, double y, double z) const {
    return (static_cast<std::size_t>(coord(z, 2)) * dims[1] + coord(y, 1)) * dims[0] + coord(x, 0);
  }
  std::size_t cellOf(const FluidParticles& p, std::size_t k) const { return cellOf(p.x[k], p.y[k], p.z[k]); }
  std::size_t count() const { return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]; }
};

}  // namespace rupture::sph
