#pragma once
// The sizes the fluid–shell contact checks against (docs/fsi-contact.md, "Pinballs"):
//   a fluid particle is a sphere of radius r_f = dx/2 (half its lattice spacing: the volume it
//   stands for), a shell node a cylinder (the seed's remark after eq. 7: cylindrical pinballs carry
//   the topological thickness of a shell) of half height t/2 along its pseudo-normal and radius
//   R_c = 0.8 Δ in its tangent plane. On a square lattice of spacing Δ every point of the
//   mid-surface is within Δ/√2 = 0.707 Δ of a node, on the clamped disc's ring lattice within
//   0.711 Δ (measured): R_c = Δ/√2 would leave slivers; 0.8 Δ covers them with 12 % to spare
//   (membrane stretch). A missing (hole) or fractured node leaves an opening of radius
//   ≈ Δ − R_c = 0.2 Δ, which widens as the crack opens.
// Contact when the particle's centre is inside the cylinder grown by r_f along the normal:
//   |s| < t/2 + r_f and ρ < R_c, s = (x_f − x_n)·n_n, ρ the in-plane distance.
// The master–slave surface under a particle is interpolated over S = 1.5 max(Δ, dx) in-plane
// (surfaceSupport): the particle's face dx² on the plate, not only the nodes nearest its centre,
// carries its load when the plate is finer than the fluid (docs/fsi-contact.md, "Footprint").
#include <algorithm>
#include <cmath>

namespace rupture::fsi {

struct ContactGeometry {
  double fluidRadius = 0;    ///< r_f (m)
  double halfThickness = 0;  ///< t/2 (m)
  double cellRadius = 0;     ///< R_c (m)
  double nodeSpacing = 0;    ///< Δ (m)

  /// The contact distance along the normal: where a resting particle's centre sits (m).
  double standOff() const { return halfThickness + fluidRadius; }
  /// In-plane radius (m) of the nodes that make the master–slave surface under a particle: 1.5 Δ,
  /// or 1.5 dx (dx = 2 r_f) where the fluid is the coarser, so that the Shepard weights
  /// (1 − ρ/S)², whose area is π S²/6 = 1.18 dx², spread the particle's load over its face.
  double surfaceSupport() const { return 1.5 * std::max(nodeSpacing, 2.0 * fluidRadius); }
  /// Largest centre distance of a contacting pair (m): the cell size of the node grid.
  double reach() const { return std::hypot(standOff(), 1.5 * nodeSpacing); }
  /// The same for the master–slave surface (m).
  double surfaceReach() const { return std::hypot(standOff() + fluidRadius, surfaceSupport()); }
};

/// R_c / Δ (see above).
inline constexpr double kCellRadiusFactor = 0.8;

inline ContactGeometry contactGeometry(double fluidSpacing, double plateThickness, double nodeSpacing) {
  return {0.5 * fluidSpacing, 0.5 * plateThickness, kCellRadiusFactor * nodeSpacing, nodeSpacing};
}

}  // namespace rupture::fsi
