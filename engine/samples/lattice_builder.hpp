#pragma once
// Builds a bonded sample on a regular lattice (sample.lattice != "random"): sites filling the box,
// bonds as far as the material style reaches (bonded/materials/: lattice springs: the lattice's
// spring families; beams: nearest neighbours; PMB: every pair within the horizon), notches, then pores carved as for random
// packings (sites whose centre falls in a pore are removed, the pores scaled by one common factor
// to reach the porosity), then sites left without bond. Site volume = the lattice's cell
// (× thickness in 2D), mass = ρ V, radius l/2 (contact), inertia of a disk/sphere of that radius.

#include "samples/sample_builder.hpp"

namespace rupture {

SampleReport buildLatticeSample(const SampleSpec& sample, const MaterialSpec& material, BondedSystem& system,
                                const Cancellation& cancel = {});

}  // namespace rupture
