#pragma once
// Regular lattices of the lattice-model review (Yu et al. 2019, section on lattice types): triangular and
// square (2D), simple-cubic and face-centred cubic (3D). `spacing` l is the nearest-neighbour
// distance. Each lattice names its spring families: the bonds a lattice model puts between sites.
//   triangular    6 neighbours at l                      node area √3/2 l²
//   square        4 at l, 4 diagonals at √2 l             node area l²
//   simple-cubic  6 at l, 12 face diagonals at √2 l       node volume l³
//   fcc           12 at l                                 node volume l³/√2
// Central springs alone need the diagonals of the square and simple-cubic lattices to resist shear.
#include <array>
#include <string>
#include <vector>

namespace rupture {

enum class LatticeKind { Random, Triangular, Square, SimpleCubic, Fcc };

/// "random" | "triangular" | "square" | "simple-cubic" | "fcc".
LatticeKind latticeKind(const std::string& name);
std::string toString(LatticeKind kind);
/// 2 for triangular and square, 3 for simple-cubic and fcc, 0 for random (any).
int latticeDimension(LatticeKind kind);

/// Area (2D) or volume (3D) per site, in units of spacing² or spacing³.
double siteMeasure(LatticeKind kind);

/// Half of the spring-family neighbour offsets (one per bond), in units of the spacing.
std::vector<std::array<double, 3>> springOffsets(LatticeKind kind);

/// Site positions filling [0, size) with a half-spacing margin (m).
std::vector<std::array<double, 3>> latticeSites(LatticeKind kind, double spacing, const std::array<double, 3>& size);

/// Number of spring-family bonds a plane normal to x cuts, per unit area (2D: per unit length and
/// per unit thickness t): n_cut = Σ_half-offsets |ξ_x| / (site measure). A straight crack costs
/// n_cut w_c per unit area when each bond breaks at energy w_c (the Griffith criterion).
double springsCutPerArea(LatticeKind kind, double spacing, double thickness);

}  // namespace rupture
