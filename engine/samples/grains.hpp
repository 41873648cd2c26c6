#pragma once
// Voronoi grains of a bonded sample (polycrystalline microstructure as in Yu et al. 2019,
// docs/references.md#yu2019; every bonded model):
// `count` seed points uniform in the sample box, drawn from their own random stream of sample.seed
// (so adding grains does not change the packing or the pores), and each particle belongs to the grain
// of its nearest seed point. Bonds whose ends lie in different grains are grain-boundary bonds: their
// failure threshold is multiplied by the boundary factor (an interblock value for every pair of grains,
// for every failure criterion).
#include <cstdint>
#include <vector>

#include "core/bond_store.hpp"
#include "core/cancellation.hpp"
#include "core/particle_store.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

/// The grain seed points (m), count × 3 (z = 0 in 2D), in grain order.
std::vector<std::array<double, 3>> grainSeeds(const SampleSpec& sample);

/// Grain index (0 … count − 1) of every particle: its nearest seed point (a grid search, O(n)).
std::vector<std::int32_t> voronoiGrains(const SampleSpec& sample, const ParticleStore& particles,
                                        const Cancellation& cancel = {});

/// Multiplies the strength (the factor on the threshold) of every bond joining two grains by
/// `factor`; returns how many there are. Call before BondStore::finalize.
std::size_t weakenGrainBoundaries(const std::vector<std::int32_t>& grain, double factor, BondStore& bonds);

}  // namespace rupture
