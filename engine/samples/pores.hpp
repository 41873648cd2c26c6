#pragma once
// Pores of a bonded sample, for random packings and lattices alike: radii uniform in
// [r_min, r_max], placed at random inside the box without overlap until their volume reaches the
// target (random sequential addition; the spec validation bounds their number and the porosity,
// bonded/bonded_spec.cpp), then carved: for each element, the smallest common scale of the pore radii
// that would swallow its centre; removing the elements in that order, up to the scale that keeps
// the pores apart and inside the box (at most 1.5), gives the removed volume closest to the
// porosity. Both stages look at the cancel flag between units of work well under 0.2 s.
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "core/cancellation.hpp"
#include "core/particle_store.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

struct Pore {
  std::array<double, 3> centre;
  double radius;
};

/// Pores until their volume (area in 2D) reaches poreVolumeTarget; throws std::runtime_error if the
/// box jams (a pore finds no free place in 20,000 tries).
std::vector<Pore> placePores(const SampleSpec& sample, double poreVolumeTarget, std::mt19937_64& rng,
                             const Cancellation& cancel);

/// Marks keep[k] = 0 for the elements the pores swallow, scales the pores to the radius actually
/// carved, and returns the porosity reached: removed element volume / all element volume.
double carvePores(const SampleSpec& sample, std::vector<Pore>& pores, const ParticleStore& particles,
                  std::vector<std::uint8_t>& keep, const Cancellation& cancel);

}  // namespace rupture
