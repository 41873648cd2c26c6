#pragma once
// Gives a built sample's bonds the fibres of anisotropic damage (damage/anisotropic_damage.hpp,
// material.anisotropic_damage): each particle's material frame (its block's angles, or its Voronoi
// grain's random frame), then each bond's fibres from its two ends' frames.
#include <cstdint>
#include <vector>

#include "bonded/sample_spec.hpp"
#include "core/bond_store.hpp"
#include "core/particle_store.hpp"

namespace rupture {

/// Each particle's frame axes. With randomGrainFrames, grain g's frame is uniformly random (a
/// rotation angle uniform in [0°, 180°) in 2D, a uniform random rotation in 3D), drawn from a stream of
/// sample.seed of its own; else its block's frame (samples/blocks.hpp) where blockAngles lists the
/// block, the default angles where it does not. `grain` is the particle's grain (samples/grains.hpp),
/// read only with randomGrainFrames.
std::vector<FrameAxes> materialFrames(const AnisotropicDamageSpec& spec, const SampleSpec& sample,
                                      const ParticleStore& particles, const std::vector<std::int32_t>& grain);

/// Sets every bond's fibres (BondStore::fibreFactor, fibreIntegrity) from its ends' frames.
void assignFibres(const AnisotropicDamageSpec& spec, int dimension, const std::vector<FrameAxes>& frames,
                  BondStore& bonds);

}  // namespace rupture
