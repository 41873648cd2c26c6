#pragma once
// What the seed measures on the plate (§2, §6): the deflection at a radius ((D_ext + d)/4 from the
// centre), the opening angle of a U tongue, the cracked length and the crack paths. All read the
// current state of the shell; SI units (m, rad).
#include <array>
#include <vector>

#include "scenarios/tank_impact/plate_geometry.hpp"

namespace rupture {

/// Mean downward deflection (m, positive towards −z) of the intact nodes on the ring of the given
/// radius (nodes within half a spacing of it).
double deflectionAtRadius(const SphShell& shell, const PlateGeometry& geometry, double radius);

/// Opening angle (rad) of a U tongue: the angle between the tongue's mean plane (its nodes inside
/// the U) and the reference plane, about the U's base line. 0 for other shapes.
double tongueOpeningAngle(const SphShell& shell, const PlateGeometry& geometry, const PlateSpec& plate);

/// Length (m) of the cracks the impact opened: fractured nodes' cells, as segments, beyond the
/// pre-cracks (each fractured node counts its spacing).
double crackedLength(const SphShell& shell, const PlateGeometry& geometry);

/// Reference positions (m) of the fractured nodes, in the order they failed — the crack paths.
std::vector<std::array<double, 2>> crackPath(const SphShell& shell, const PlateGeometry& geometry);

}  // namespace rupture
