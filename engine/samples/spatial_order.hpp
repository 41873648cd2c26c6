#pragma once
// Spatial numbering of a packed sample: elements renumbered strip by strip (strips of 8 mean radii
// across y, serpentine along x), bonds sorted by (i, j). The packing places elements in random
// order, so a bond's two ends were ~N/3 indices apart and every step read its far end, its loads
// and its gather at random (measured: 10 % of a 2D dynamic-tension run's CPU). The sample is the
// same set of elements and bonds; sums over bonds and contacts run in another order, so results
// agree with a randomly numbered sample to rounding, not bit for bit.
#include "bonded/bonded_system.hpp"

namespace rupture {

/// Renumbers the particles and bonds of an unfinalised system (call before BondedSystem::initialize).
/// stripWidth > 0 (m). Deterministic: ties broken by the previous index.
void orderSpatially(BondedSystem& system, double stripWidth);

}  // namespace rupture
