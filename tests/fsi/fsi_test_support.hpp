#pragma once
// Small set-ups for the fluid–shell contact tests: a water column in a rigid cylinder standing on
// a clamped SPH-shell disc (optionally with a central hole), built with the tank-impact lattice.
#include <cmath>
#include <memory>
#include <numbers>

#include "fsi/fluid_shell_coupling.hpp"
#include "scenarios/tank_impact/tank_lattice.hpp"
#include "shell/shell_nodes.hpp"
#include "shell/sph_shell.hpp"
#include "sph/sph_system.hpp"

namespace rupture::fsitest {

struct ColumnOnPlate {
  sph::SphSystem fluid;
  std::unique_ptr<SphShell> plate;
  std::unique_ptr<fsi::FluidShellCoupling> coupling;
  TankLattice lattice;
};

/// Nodes of a clamped disc of radius `radius` at spacing `spacing`, without those inside `hole`.
inline ShellNodes discNodes(double radius, double spacing, double hole) {
  const ShellNodes all = clampedDiskNodes(radius, spacing, 0);
  ShellNodes kept;
  kept.spacing = all.spacing;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (std::hypot(all.x[i], all.y[i]) < hole) continue;
    kept.x.push_back(all.x[i]);
    kept.y.push_back(all.y[i]);
    kept.kernelVolume.push_back(all.kernelVolume[i]);
    kept.integrationArea.push_back(all.integrationArea[i]);
    kept.clamped.push_back(all.clamped[i]);
  }
  return kept;
}

struct ColumnSetup {
  double spacing = 0.004, radius = 0.02, height = 0.06, hole = 0.0;
  double soundSpeed = 15.0, alpha = 0.1, gravity = 9.81;
  bool piston = false;
  double pistonMass = 0.0;          ///< kg on the real section π R²
  ShellParameters plate;
  ContactMethod method = ContactMethod::Pinball;
};

inline std::unique_ptr<ColumnOnPlate> columnOnPlate(const ColumnSetup& c) {
  auto out = std::make_unique<ColumnOnPlate>();
  sph::FluidModel& m = out->fluid.model;
  m.dimension = 3;
  m.spacing = c.spacing;
  m.eos.soundSpeed = c.soundSpeed;
  m.alpha = c.alpha;
  m.gravity = {0, 0, -c.gravity};
  TankLatticeParams q;
  q.spacing = c.spacing;
  q.radius = c.radius;
  q.height = c.height;
  q.bottom = 0.5 * c.plate.thickness;
  q.piston = c.piston;
  q.pistonMass = c.pistonMass;
  q.pistonSpeed = 0.0;
  q.gravity = c.gravity;
  out->lattice = buildTankLattice(out->fluid, q);
  out->fluid.initialise();
  out->plate = std::make_unique<SphShell>(discNodes(c.radius, c.spacing, c.hole), c.plate);
  out->coupling = std::make_unique<fsi::FluidShellCoupling>(
      out->fluid, *out->plate, c.method, fsi::contactGeometry(c.spacing, c.plate.thickness, c.spacing));
  return out;
}

}  // namespace rupture::fsitest
