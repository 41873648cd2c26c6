#pragma once
// Static partition of a bonded sample's reference configuration by recursive coordinate bisection
// (Berger and Bokhari 1987): the set is cut across its longest extent at the point that splits its
// work in the ratio of the ranks on each side, and each half is cut again, until each sub-domain
// has one rank. Bricks, not slabs: for many ranks the halo (the surface) stays small against the
// interior (the volume), and with bonds that never form (only break) the partition of the
// reference configuration holds for the whole run, as in CabanaPD and LAMMPS's static balance.
// Work of a particle: 1 + its bonds (the loops' cost is per particle and per bond slot).
#include <vector>

#include "core/bond_store.hpp"
#include "core/particle_store.hpp"

namespace rupture {

/// The rank that owns each particle, in [0, parts). Deterministic: ties along an axis are broken by
/// the particle index, so every rank computes the same partition from the same sample.
std::vector<int> bisectCoordinates(const ParticleStore& particles, const BondStore& bonds, int parts);

}  // namespace rupture
