#pragma once
// The piston-column particles on a lattice of spacing dx centred on the tube axis (x = 0, and
// y = 0 in 3D), the bottom face at vertical 0: the water column (hydrostatic densities), the tube
// wall and the bottom (`wall_layers` layers each, fixed bodies) and the piston (`wall_layers`
// layers above the column, free or prescribed, guided along the axis into the column).
#include "scenarios/piston_column/piston_column_spec.hpp"
#include "sph/sph_system.hpp"

namespace rupture {

/// Body indices in SphSystem::bodies.
enum ColumnBody : std::int32_t { kColumnTube = 0, kColumnBottom = 1, kColumnPiston = 2 };

struct ColumnLattice {
  double dx;
  int nR, nH;        ///< tube radius and column height (cells)
  double area = 0;   ///< piston face and bottom area: m² (3D), m per metre of depth (2D)
  double R() const { return nR * dx; }
  double H() const { return nH * dx; }
};

/// Sets s.model from the spec, fills s.particles and s.bodies. The piston's mass per unit face
/// area M/(π D²/4) is what sets its deceleration, so its mass is that times the lattice's section
/// (a 2D slice: per metre of depth). Call s.initialise() next.
ColumnLattice buildPistonColumn(sph::SphSystem& s, const PistonColumnSpec& spec);

}  // namespace rupture
