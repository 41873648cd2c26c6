#pragma once
// What the seed measures on the plate (§2, §6): the deflection at a radius ((D_ext + d)/4 from the
// centre), the opening angle of a U tongue, the cracked length and the crack paths. All read the
// current state of the shell; SI units (m, rad).
#include <array>
#include <vector>

#include "scenarios/tank_impact/plate_geometry.hpp"

namespace rupture {

/// Downward deflection (m, positive towards −z) at the given radius: the mean deflection of the
/// intact nodes of each ring of the disc (rings at r_k = k Δ), interpolated linearly between the
/// two rings that bracket the radius (the nearest ring within Δ/2 where only one has intact nodes).
/// NaN where no ring with intact nodes lies within Δ of the radius (inside the hole).
double deflectionAtRadius(const SphShell& shell, const PlateGeometry& geometry, double radius);

/// Opening angle (rad) of a U tongue (PlateGeometry::hinge is the uncut side of the U), positive
/// when the tongue swings down (−z): its inclination to the plate's reference plane, the rotation
/// that best maps the tongue's intact nodes from their reference to their current positions in
/// the plane normal to the hinge, up to a translation: α = atan2(−Σ d̃_i w̃_i, Σ d̃_i ũ_i), d_i the
/// reference distance from the hinge, u_i and w_i the current in-plane and vertical distances, ˜
/// their deviations from the tongue's mean. Exact for a rigid rotation of any angle up to 180°
/// about any point, so the hinge's own sinking as the plate dishes adds nothing. 0 for other shapes.
double tongueOpeningAngle(const SphShell& shell, const PlateGeometry& geometry, const PlateSpec& plate);

/// Length (m) of the cracks the impact opened, beyond the pre-cracks (cuts, not fractured nodes):
/// Σ √V_i over the fractured nodes, each cracked cell counting its side (a one-cell-wide band of
/// length ℓ holds about ℓ/Δ cells of area Δ²).
double crackedLength(const SphShell& shell, const PlateGeometry& geometry);

/// Fraction of the spot face's rim along which the plate has torn, in [0, 1]: the union of the
/// angular widths √V_i / r_i of the fractured nodes whose reference radius lies within `band` of
/// `rimRadius` (m), over 2π. The seed's "rupture of the bottom at the level of the spot-facing
/// circumference" (§3.2) reads as a fraction near 1; a crack that runs in from a pre-crack touches
/// it only where it reaches the rim.
double rimTornFraction(const SphShell& shell, const PlateGeometry& geometry, double rimRadius, double band);

/// Reference positions (m) of the fractured nodes, in the order they failed (SphShell::fractureOrder)
/// — the crack paths.
std::vector<std::array<double, 2>> crackPath(const SphShell& shell, const PlateGeometry& geometry);

}  // namespace rupture
