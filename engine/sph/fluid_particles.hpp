#pragma once
// Structure-of-arrays store of one SPH particle set: fluid particles and the boundary particles of
// rigid bodies (walls, pistons) side by side: walls enter the same pair loop as the fluid.
// Unlike the bonded store, SPH particles are reordered: sorting them in cell order keeps
// neighbours near in memory, and `id` remembers each particle's creation index so that output is
// always written in the same order.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/staggered_allocator.hpp"
#include "rupture/state_archive.hpp"

namespace rupture::sph {

/// body[k] of a fluid particle; boundary particles hold their body's index (>= 0).
inline constexpr std::int32_t kFluid = -1;

struct FluidParticles {
  // Each field is a ParticleArray, staggered within the page: the integrator's and the pair
  // loop's passes walk up to 22 of them at once (core/staggered_allocator.hpp).
  // State (m, m/s, kg/m³).
  ParticleArray<double> x, y, z;
  ParticleArray<double> vx, vy, vz;
  ParticleArray<double> rho;
  // Estimates at the end of the current step, read by the pair loop (see SphSystem::step).
  ParticleArray<double> vxEst, vyEst, vzEst, rhoEst;
  // Per particle from rhoEst before each pair loop: p (Pa) (the fluid's from the equation of state,
  // the boundary's extrapolated).
  ParticleArray<double> pressure;
  // Rates from the pair loop: acceleration without gravity (m/s²) and dρ/dt (kg/m³/s).
  ParticleArray<double> ax, ay, az, drho;
  // Constant: mass (kg; kg/m in 2D), body (kFluid or a body index), creation index.
  ParticleArray<double> mass;
  ParticleArray<std::int32_t> body, id;

  std::size_t size() const { return x.size(); }
  bool isFluid(std::size_t k) const { return body[k] == kFluid; }

  /// Appends a particle at rest.
  void add(double px, double py, double pz, double m, double density, std::int32_t bodyIndex);

  /// Reorders every array so that new position k holds old particle order[k].
  void permute(const std::vector<std::int32_t>& order);

  /// Every array: the particles are re-sorted as the run goes, so even the constant ones (mass,
  /// body, id) are in the order of the moment.
  void exchangeState(StateArchive& archive);
  /// The same with the caller's scratch (kept between calls, the reorder allocates nothing).
  void permute(const std::vector<std::int32_t>& order, ParticleArray<double>& scratch,
               ParticleArray<std::int32_t>& indexScratch);

  /// Fills `out` (size n) with field[k] placed at id[k]: the creation order used for output.
  void inCreationOrder(std::span<const double> field, std::vector<double>& out) const;
};

}  // namespace rupture::sph
