#pragma once
// Pre-cracks (sample.notches): the bonds whose segment crosses a notch are removed, in any bonded
// sample. In 2D a notch is the segment [start, end]; in 3D the strip that segment sweeps along z
// through the whole sample, so both reduce to a segment–segment test in the x-y plane.
#include <cstddef>
#include <vector>

#include "core/bond_store.hpp"
#include "core/particle_store.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

/// True when the segments [a, b] and [c, d] of the x-y plane cross (touching counts).
bool segmentsCross(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy);

/// Removes the bonds crossing any notch (before finalize), recording each as a cut pair
/// (BondStore::cutPairs: contact treats it as a broken bond); returns how many were removed.
std::size_t cutNotches(const std::vector<Notch>& notches, const ParticleStore& particles, BondStore& bonds);

}  // namespace rupture
