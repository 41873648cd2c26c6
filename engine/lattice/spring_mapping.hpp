#pragma once
// Spring stiffnesses of the Hookean (central) and Born (normal + shear) lattice models from the target
// Young's modulus E and Poisson ratio ν, by energy equivalence under a homogeneous strain
// (docs/references.md#eq-lattice; derivations in docs/lattice-models.md). 2D lattices are in plane
// stress with thickness t. With r = k_s/k_n the same on every family (the square lattice's diagonal
// springs are half as stiff, which makes it isotropic):
//   triangular     ν = (1 − r)/(3 + r)   E t = 2√3 k_n (1 + r)/(3 + r)
//   square         ν = (1 − r)/(3 + r)   E t = 4 k_n (1 + r)/(3 + r)
//   simple-cubic   ν = (1 − r)/(4 + r)   E l = 5 k_n (2 + 3r)/(4 + r)
//   fcc            ν = (1 − r)/(3 + r)   E l = 2√2 k_n (1 + 3r)/(3 + r)   (cubic: E, ν along a lattice axis)
// k_s >= 0 bounds ν from above: 1/3 (1/4 for simple-cubic); ν -> −1 as k_s/k_n -> ∞. Hookean
// springs (r = 0) fix ν at that bound.
#include <string>

#include "lattice/lattice_geometry.hpp"

namespace rupture {

struct PoissonRange {
  double min, max;  ///< admissible ν: (min, max] for Born, [max, max] for Hookean
  bool fixed;       ///< Hookean: ν is a property of the lattice, not a choice
};

/// The Poisson ratios a lattice model can reach (`born` false: Hookean).
PoissonRange poissonRange(LatticeKind lattice, bool born);

struct SpringConstants {
  double normalStiffness;  ///< k_n of the nearest-neighbour family (N/m)
  double shearRatio;       ///< r = k_s / k_n (1); 0 for Hookean
};

/// Springs giving E (Pa) and ν; ν must lie in poissonRange (checked by the caller).
SpringConstants springConstants(LatticeKind lattice, bool born, double youngModulus, double poissonRatio,
                                double spacing, double thickness);

/// Stiffness factor of a bond family relative to the nearest neighbours: ½ for the square
/// lattice's diagonals, 1 otherwise.
double familyStiffnessFactor(LatticeKind lattice, double restLength, double spacing);

/// The (E, ν) a lattice gives for k_n and r (the forward map, for checks and tests).
struct LatticeElasticity { double youngModulus, poissonRatio; };
LatticeElasticity latticeElasticity(LatticeKind lattice, double normalStiffness, double shearRatio, double spacing,
                                    double thickness);

}  // namespace rupture
