#include "scenarios/piston_column/piston_column_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rupture {

/// Sites on a lattice of spacing dx centred on the tube axis (x = 0, and y = 0 in 3D), the bottom
/// face at vertical 0. Tube and bottom: `layers` layers; piston: `layers` layers above the column.
ColumnLattice buildPistonColumn(sph::SphSystem& s, const PistonColumnSpec& spec) {
  s.model = io::fluidModel(spec.fluid, spec.resolution, spec.dimension, spec.soundSpeed, spec.gravity);
  const sph::EquationOfState& eos = s.model.eos;
  const int dim = spec.dimension, layers = spec.resolution.wallLayers;
  ColumnLattice g{spec.resolution.spacing, std::max(2, static_cast<int>(std::lround(0.5 * spec.diameter / spec.resolution.spacing))),
                  std::max(4, static_cast<int>(std::lround(spec.columnHeight / spec.resolution.spacing)))};
  const double dx = g.dx, rho0 = eos.referenceDensity, R = g.R(), Rw = R + layers * dx;
  const double mass = rho0 * std::pow(dx, dim);
  s.bodies.assign(3, {});
  s.bodies[kColumnTube].name = "tube";
  s.bodies[kColumnBottom].name = "bottom";
  s.bodies[kColumnPiston].name = "piston";
  auto hydrostatic = [&](double v) { return v < g.H() ? eos.density(rho0 * spec.gravity * (g.H() - v)) : rho0; };
  const int top = g.nH + 3 * layers;  // the tube goes on above the piston
  const int n = g.nR + layers;
  const int j0 = dim == 3 ? -n : 0, j1 = dim == 3 ? n : 1;
  std::size_t crossSection = 0;
  for (int k = -layers; k < top; ++k) {
    s.cancel.throwIfRequested();  // one layer: at most a few hundred thousand sites
    for (int j = j0; j < j1; ++j)
      for (int i = -n; i < n; ++i) {
        const double x = (i + 0.5) * dx, y = dim == 3 ? (j + 0.5) * dx : 0.0, v = (k + 0.5) * dx;
        const double r2 = x * x + y * y;
        const bool inTube = r2 < R * R, inWall = r2 < Rw * Rw;
        const double px = x, py = dim == 3 ? y : v, pz = dim == 3 ? v : 0.0;
        if (!inWall) continue;
        if (k < 0) s.particles.add(px, py, pz, mass, hydrostatic(v), kColumnBottom);
        else if (!inTube) s.particles.add(px, py, pz, mass, hydrostatic(v), kColumnTube);
        else if (k < g.nH) {
          s.particles.add(px, py, pz, mass, hydrostatic(v), sph::kFluid);
          if (k == 0) ++crossSection;
        } else if (k < g.nH + layers) {
          s.particles.add(px, py, pz, mass, rho0, kColumnPiston);
        }
      }
  }
  g.area = static_cast<double>(crossSection) * std::pow(dx, dim - 1);
  sph::RigidBody& piston = s.bodies[kColumnPiston];
  piston.axis = {0, 0, 0};
  piston.axis[dim - 1] = -1.0;  // into the column
  piston.motion = spec.piston.motion;
  piston.history = spec.piston.history;
  piston.speed = spec.piston.motion == sph::BodyMotion::Free ? spec.piston.speed : spec.piston.history.at(0.0);
  // The piston's mass per unit face area M/(π D²/4) is what sets its deceleration; a 2D slice
  // (per metre of depth) and the lattice's cross-section keep it.
  piston.mass = spec.piston.mass / (0.25 * std::numbers::pi * spec.diameter * spec.diameter) * g.area;
  return g;
}

}  // namespace rupture
