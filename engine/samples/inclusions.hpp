#pragma once
// Second-phase inclusions of a bonded sample (the "second phase" of Yu et al. 2019,
// docs/references.md#yu2019; every bonded model):
// circular (2D) or spherical (3D) regions with radii uniform in [r_min, r_max], placed at random
// without overlap until their volume reaches volume_fraction of the box (the pores' random
// sequential addition, samples/pores.hpp, on a random stream of its own, so inclusions change neither
// the packing nor the pores). An element whose centre lies in an inclusion belongs to it; its mass
// is scaled by the density factor. A bond with both ends inside is an inclusion bond (stiffness and
// strength scaled by their factors); one end inside, an interface bond: its stiffness is the two
// half-bonds in series, 2a/(1 + a) of the matrix's, its strength scaled by the interface factor.
// Stiffness factors need a per-bond stiffness (hookean, born, pmb); beam parameters are global.
#include <cstdint>
#include <vector>

#include "core/bond_store.hpp"
#include "core/cancellation.hpp"
#include "core/particle_store.hpp"
#include "samples/pores.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

/// The inclusions of a sample (none when its volume fraction is 0).
std::vector<Pore> placeInclusions(const SampleSpec& sample, const Cancellation& cancel = {});

/// 1 for the particles whose centre lies in an inclusion, else 0 (a grid search, O(particles)).
std::vector<std::uint8_t> insideInclusions(const std::vector<Pore>& inclusions, const ParticleStore& particles);

/// Scales masses (and inertias) of the inclusion particles and the stiffness and strength of the
/// inclusion and interface bonds; call before BondStore::finalize.
void applyInclusionProperties(const InclusionSpec& spec, const std::vector<std::uint8_t>& inside,
                              ParticleStore& particles, BondStore& bonds);

}  // namespace rupture
