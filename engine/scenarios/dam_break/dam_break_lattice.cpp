#include "scenarios/dam_break/dam_break_lattice.hpp"

#include <algorithm>
#include <cmath>

namespace rupture {

namespace {

DamBreakLattice lattice(const DamBreakSpec& s) {
  const double dx = s.resolution.spacing;
  auto cells = [dx](double length) { return std::max(1, static_cast<int>(std::lround(length / dx))); };
  const DamBreakGeometry& g = s.geometry;
  return {dx, cells(g.columnWidth), cells(g.columnHeight), cells(g.tankLength), cells(g.tankHeight),
          g.width ? cells(*g.width) : 1};
}

}  // namespace

DamBreakLattice buildDamBreak(sph::SphSystem& s, const DamBreakSpec& spec) {
  s.model = io::fluidModel(spec.fluid, spec.resolution, spec.dimension, spec.soundSpeed, spec.gravity);
  const DamBreakLattice g = lattice(spec);
  const sph::EquationOfState& eos = s.model.eos;
  const double dx = g.dx, rho0 = eos.referenceDensity;
  const int dim = spec.dimension, layers = spec.resolution.wallLayers;
  const double mass = rho0 * std::pow(dx, dim);
  s.bodies.assign(1, {});
  s.bodies[0].name = "tank";
  auto hydrostatic = [&](double vertical) { return eos.density(rho0 * spec.gravity * (g.H() - vertical)); };
  const int j0 = dim == 3 ? -layers : 0, j1 = dim == 3 ? g.nW + layers : 1;
  for (int k = -layers; k < g.nT; ++k) {
    s.cancel.throwIfRequested();  // one layer: at most a few hundred thousand sites
    for (int j = j0; j < j1; ++j)
      for (int i = -layers; i < g.nL + layers; ++i) {
        const double x = (i + 0.5) * dx, across = (j + 0.5) * dx, v = (k + 0.5) * dx;
        const bool inside = i >= 0 && i < g.nL && k >= 0 && (dim == 2 || (j >= 0 && j < g.nW));
        const double px = x, py = dim == 3 ? across : v, pz = dim == 3 ? v : 0.0;
        if (!inside) {
          // Walls beside and under the column start at the column's hydrostatic density.
          const bool loaded = i < g.nA && k < g.nH;
          s.particles.add(px, py, pz, mass, loaded ? hydrostatic(v) : rho0, 0);
        } else if (i < g.nA && k < g.nH) {
          s.particles.add(px, py, pz, mass, hydrostatic(v), sph::kFluid);
        }
      }
  }
  return g;
}

}  // namespace rupture
