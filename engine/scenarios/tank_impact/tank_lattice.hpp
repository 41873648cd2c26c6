#pragma once
// The tank-impact fluid particles on a lattice of spacing dx centred on the tank axis (z up): the
// water column from the plate's upper face z0 = t/2 to z0 + H (hydrostatic densities), the
// cylinder's wall (`wall_layers` rings of fixed boundary particles from `wall_layers` layers below
// z0, around the plate's clamped rim, up past the piston) and
// the piston (`wall_layers` layers on top of the column, free, guided along −z). There is no
// bottom: the plate (an SphShell) closes the tube through the fluid–shell contact (engine/fsi).
// The pattern of buildPistonColumn, with the rigid bottom replaced by the plate.
#include <cstdint>

#include "scenarios/tank_impact/tank_impact_spec.hpp"
#include "sph/sph_system.hpp"

namespace rupture {

/// Body indices in SphSystem::bodies.
enum TankBody : std::int32_t { kTankWall = 0, kTankPiston = 1 };

struct TankLatticeParams {
  double spacing = 0.002;      ///< dx (m)
  double radius = 0.04;        ///< inner radius of the cylinder D/2 (m)
  double height = 0.18;        ///< water height H (m)
  double bottom = 0.001;       ///< z of the water's lower face: the plate's upper face t/2 (m)
  int wallLayers = 3;
  double pistonMass = 245.0;   ///< M (kg) on the real section π D²/4
  double pistonSpeed = 5.0;    ///< V (m/s), downwards
  double gravity = 9.81;       ///< m/s² along −z, for the hydrostatic start
  bool piston = true;          ///< false: a free surface on top (the piston body stays empty)
};

struct TankLattice {
  double dx = 0;
  int nR = 0, nH = 0;  ///< radius and height (cells)
  double bottom = 0;   ///< z of the water's lower face (m)
  double area = 0;     ///< lattice cross-section (m²): fluid sites in one layer × dx²
  std::size_t fluidParticles = 0;
  double R() const { return nR * dx; }
  double H() const { return nH * dx; }
};

/// The lattice of a spec: the fluid spacing, the bore, the water from the plate's upper face, the
/// carriage's mass and speed (the run and its preview both lay this one).
TankLatticeParams tankLatticeParams(const TankImpactSpec& spec);

/// Fills s.particles and s.bodies (s.model must be set). The piston's mass per unit area M/(π R²)
/// is kept on the lattice's section. Call s.initialise() next.
TankLattice buildTankLattice(sph::SphSystem& s, const TankLatticeParams& params);

}  // namespace rupture
