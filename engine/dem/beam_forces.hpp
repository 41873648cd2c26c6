#pragma once
// One beam evaluated on its own (tests, diagnostics). The step's loops are core/bond_loop.hpp.
#include <cstddef>

#include "core/bond_store.hpp"
#include "core/particle_store.hpp"
#include "dem/beam_bond.hpp"

namespace rupture {

/// Evaluates the law for bond b in the current configuration (for tests, snapshots and diagnostics).
BeamResponse beamResponseOf(const BeamParameters& beam, const ParticleStore& particles,
                            const BondStore& bonds, std::size_t b);

}  // namespace rupture
