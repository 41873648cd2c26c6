#pragma once
// The tank-impact bottom plate as an SPH shell: the Ø D spot face of nodes at spacing Δ
// (clampedDiskNodes: concentric rings), clamped at its rim or continued by the thick bottom out to
// its clamp (plate.clamp, the step midway between two rings; refined about the step by
// plate.bottom.step_spacing: ringDiskNodes on refinedRingRadii), the central hole and the pre-cracks.
//
// Hole: no node is created inside it (r < r_h); the innermost ring kept carries the part of its
// annulus outside the hole, so the integration areas sum to π(R² − r_h²). The hole's edge is a
// free edge because the corrected gradients only see the nodes that exist; links whose segment
// passes through the hole (chords between edge nodes) are cut as well (visibility criterion,
// buildPlate), so no material bridges the hole.
//
// Pre-cracks: segments whose crossing links are cut (SphShell::cutAlongSegment cuts only links
// that cross strictly, so a node lying on a crack would keep both lips joined). The ring lattice
// has no straight node rows, so every crack line is moved sideways by the smallest shift
// (|δ| <= Δ/2) that keeps the nodes along it at least Δ/10 off the line; the shifts are the only
// difference from the nominal geometry (docs/tank-impact.md, "Pre-cracks").
#include <array>
#include <cstddef>
#include <vector>

#include "scenarios/tank_impact/tank_impact_spec.hpp"
#include "shell/shell_nodes.hpp"
#include "shell/sph_shell.hpp"

namespace rupture {

struct PlateSegment {
  std::array<double, 2> a, b;  ///< end points in the reference plane (m)
};

struct PlateGeometry {
  ShellNodes nodes;                      ///< reference nodes (hole nodes excluded)
  std::vector<PlateSegment> precracks;   ///< cut segments (empty for none / hole). U: left arm, base, right arm
  double holeRadius = 0.0;               ///< m
  /// U only: the line about which the tongue opens, from the left arm's open end to the right's
  /// (the uncut side of the U), and the nodes of the tongue (inside the U).
  PlateSegment hinge{};
  std::vector<std::size_t> tongueNodes;
};

/// Sides of the polygon, inscribed in the hole's edge, along which buildPlate cuts the links that
/// pass through the hole (its sagitta is 0.12 % of the radius).
inline constexpr int kHoleEdgeSides = 64;

/// Whether the plate's rings are refined about the step (plate.bottom.step_spacing finer than the
/// resolved plate spacing): refinedRingRadii with the band two spacings wide on each side.
bool plateRefinedAtStep(const PlateSpec& plate);

/// Checks that the plate is a shell that its node spacing resolves and that the pre-crack fits
/// inside it; throws SpecError naming the plate field (plate.spacing, plate.thickness,
/// plate.precrack.hole_diameter, .length, .width).
void validatePlateGeometry(const PlateSpec& plate);

/// Throws SpecError naming the plate field when a pre-crack does not fit the plate or is finer
/// than the node spacing (validatePlateGeometry).
PlateGeometry plateGeometry(const PlateSpec& plate);

/// The shell with the links through the hole and across the pre-cracks cut.
SphShell buildPlate(const PlateSpec& plate, const PlateGeometry& geometry);

}  // namespace rupture
