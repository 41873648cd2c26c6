#pragma once
// The two bond loops of the DEM step: evaluate every beam (one pass over the bond arrays, written
// per bond, vectorised), then gather the bond loads onto particles through the incidence lists
// (one pass over particles). No atomics, and the result does not depend on the thread count.
#include <cstddef>

#include "core/bond_store.hpp"
#include "core/particle_store.hpp"
#include "dem/beam_bond.hpp"

namespace rupture {

/// Evaluates all beams, breaks those whose Rankine stress reaches σ_f, and stores per-bond loads.
/// Returns the number of bonds that broke in this call.
std::size_t computeBeamLoads(const BeamParameters& beam, const ParticleStore& particles, BondStore& bonds);

/// Sets each particle's force and torque to the sum of its bonds' loads (overwrites f and t).
void gatherBondLoads(const BondStore& bonds, ParticleStore& particles);

/// Elastic energy stored in the intact beams (J).
double beamElasticEnergy(const BeamParameters& beam, const ParticleStore& particles, const BondStore& bonds);

/// Evaluates the law for bond b in the current configuration (for tests, snapshots and diagnostics).
BeamResponse beamResponseOf(const BeamParameters& beam, const ParticleStore& particles,
                            const BondStore& bonds, std::size_t b);

}  // namespace rupture
