#pragma once
// The tank-impact bottom plate as an SPH shell: the clamped Ø D disc of nodes at spacing Δ, the
// central hole (its nodes fractured: they carry nothing and move freely, and are removed from the
// plate), and the pre-cracks as segments whose crossing links are cut (SphShell::cutAlongSegment).
// Placed between node rows so that no link only touches a crack at a node.
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
  std::vector<PlateSegment> precracks;   ///< cut segments (empty for none / hole)
  double holeRadius = 0.0;               ///< m
};

/// Throws SpecError naming the plate field when a pre-crack does not fit the plate or is finer
/// than the node spacing.
PlateGeometry plateGeometry(const PlateSpec& plate);

/// The shell with the pre-cracks cut.
SphShell buildPlate(const PlateSpec& plate, const PlateGeometry& geometry);

}  // namespace rupture
