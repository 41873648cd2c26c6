#pragma once
// The dam-break particles: the column and the tank walls on a lattice of spacing dx, lengths
// rounded to whole spacings. Fluid sites at ((i + ½) dx, ...); the wall behind the column is at
// x = 0, the floor at vertical 0; walls of `wall_layers` layers, open top. Densities start
// hydrostatic (the Tait or acoustic inversion of ρ0 g (H − z)).
#include "scenarios/dam_break/dam_break_spec.hpp"
#include "sph/sph_system.hpp"

namespace rupture {

struct DamBreakLattice {
  double dx;
  int nA, nH, nL, nT, nW;  ///< column width, column height, tank length, tank height, width (cells)
  double a() const { return nA * dx; }
  double H() const { return nH * dx; }
  double L() const { return nL * dx; }
  double T() const { return nT * dx; }
  double W() const { return nW * dx; }
};

/// Sets s.model from the spec, fills s.particles and s.bodies (body 0: the tank). Call
/// s.initialise() next.
DamBreakLattice buildDamBreak(sph::SphSystem& s, const DamBreakSpec& spec);

}  // namespace rupture
