#pragma once
// The block of every particle (sample.blocks): the id of the last box holding its centre at build
// time, 1 when none does. Interblock critical values and anisotropic damage's block frames read it.
#include <vector>

#include "bonded/sample_spec.hpp"
#include "core/particle_store.hpp"

namespace rupture {

std::vector<int> particleBlocks(const SampleSpec& sample, const ParticleStore& particles);

}  // namespace rupture
