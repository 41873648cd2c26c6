#include "scenarios/tank_impact/tank_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rupture {

TankLatticeParams tankLatticeParams(const TankImpactSpec& spec) {
  TankLatticeParams lattice;
  lattice.spacing = spec.resolution.spacing;
  lattice.radius = 0.5 * spec.innerDiameter;
  lattice.height = spec.waterHeight;
  lattice.bottom = 0.5 * spec.plate.shell.thickness;
  lattice.wallLayers = spec.resolution.wallLayers;
  lattice.pistonMass = spec.impactor.mass;
  lattice.pistonSpeed = spec.impactor.speed;
  lattice.gravity = spec.gravity;
  return lattice;
}

TankLattice buildTankLattice(sph::SphSystem& s, const TankLatticeParams& q) {
  const sph::EquationOfState& eos = s.model.eos;
  TankLattice g;
  g.dx = q.spacing;
  g.nR = std::max(2, static_cast<int>(std::lround(q.radius / q.spacing)));
  g.nH = std::max(2, static_cast<int>(std::lround(q.height / q.spacing)));
  g.bottom = q.bottom;
  const int layers = q.wallLayers;
  const double dx = g.dx, rho0 = eos.referenceDensity, R = g.R(), Rw = R + layers * dx;
  const double mass = rho0 * dx * dx * dx;
  s.bodies.assign(2, {});
  s.bodies[kTankWall].name = "cylinder";
  s.bodies[kTankPiston].name = "piston";
  auto hydrostatic = [&](double z) {
    const double depth = g.bottom + g.H() - z;
    return depth > 0 ? eos.density(rho0 * q.gravity * depth) : rho0;
  };
  const int top = g.nH + 3 * layers;  // the cylinder goes on above the piston
  const int n = g.nR + layers;
  std::size_t crossSection = 0;
  // The cylinder goes down `layers` layers past the water's lower face, around the plate's clamped
  // rim, so that no water squeezes out between the wall and the plate.
  for (int k = -layers; k < top; ++k) {
    s.cancel.throwIfRequested();  // one layer: at most a few hundred thousand sites
    for (int j = -n; j < n; ++j)
      for (int i = -n; i < n; ++i) {
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx, z = g.bottom + (k + 0.5) * dx;
        const double r2 = x * x + y * y;
        if (r2 >= Rw * Rw) continue;
        if (k < 0 && r2 < R * R) continue;
        if (r2 >= R * R) s.particles.add(x, y, z, mass, hydrostatic(z), kTankWall);
        else if (k < g.nH) {
          s.particles.add(x, y, z, mass, hydrostatic(z), sph::kFluid);
          ++g.fluidParticles;
          if (k == 0) ++crossSection;
        } else if (q.piston && k < g.nH + layers) {
          s.particles.add(x, y, z, mass, rho0, kTankPiston);
        }
      }
  }
  g.area = static_cast<double>(crossSection) * dx * dx;
  sph::RigidBody& piston = s.bodies[kTankPiston];
  piston.axis = {0, 0, -1};  // into the column
  piston.motion = q.piston ? sph::BodyMotion::Free : sph::BodyMotion::Fixed;
  piston.speed = q.piston ? q.pistonSpeed : 0.0;
  piston.mass = q.pistonMass / (std::numbers::pi * q.radius * q.radius) * g.area;
  return g;
}

}  // namespace rupture
