#pragma once
// The SPH pair loop: for every particle a, from its neighbour list (Caleyron et al. 2013 eqs. 4–5;
// Monaghan 1992; docs/references.md#eq-sph),
//   dρ_a/dt = Σ_b m_b v_ab·∇_a W_ab  [+ δ-SPH diffusion, fluid–fluid pairs, see fluid_model.hpp]
//   dv_a/dt = −Σ_b m_b (p_a/ρ_a² + p_b/ρ_b² + Π_ab) ∇_a W_ab          (gravity added by the integrator)
//   Π_ab = (−α c0 μ_ab + β μ_ab²)/ρ̄_ab if v_ab·x_ab < 0, else 0;  μ_ab = h v_ab·x_ab/(r² + 0.01 h²)
// with x_ab = x_a − x_b, ∇_a W_ab = F(r) x_ab (cubic spline), velocities and densities taken from
// the step's estimates (vxEst…, rhoEst). c̄_ab is taken as c0 (weakly compressible: |ρ/ρ0 − 1|
// stays near 1 %, so the local sound speeds differ from c0 by about 3 %).
// Boundary particles first take the pressure extrapolated from the fluid around them (Adami, Hu &
// Adams 2012, eq. 27; ρ_w from the EOS inverse), then get the momentum sum from their fluid
// neighbours: m_w·a_w is the fluid's force on them, exactly the opposite of theirs on the fluid.
// Each pair is computed once (half lists) and added to both particles: every chunk of the loop
// (NeighbourList::chunks) sums into its own buffer, and the buffers are added in chunk order
// afterwards: no atomics, and the same sums in the same order for any thread count.
#include <array>
#include <span>
#include <vector>

#include "core/cancellation.hpp"
#include "core/scratch_vector.hpp"
#include "sph/fluid_model.hpp"
#include "sph/fluid_particles.hpp"
#include "sph/neighbour_list.hpp"

namespace rupture::sph {

/// What the time-step rule needs from one evaluation (Monaghan & Kos 1999).
struct RateExtremes {
  double maxViscousMu = 0;   ///< max over pairs within the support of |μ_ab| (m/s)
  double maxAcceleration = 0;///< max over fluid particles of |dv/dt + g| (m/s²)
  double maxDensity = 0;     ///< max over fluid particles of ρ_est (kg/m³)
};

/// Scratch of the pair loop, kept between steps so that nothing is allocated per step.
struct RateWorkspace {
  /// What the pair loop reads of a neighbour, in one 64-byte record (one cache line).
  struct alignas(64) Packed {
    double x, y, z, pressureOverRho2, vx, vy, vz, inverseRho;
  };
  ScratchVector<Packed> packed;
  ScratchVector<double> sums;  ///< per chunk, 4 per touched particle: ax, ay, az, dρ/dt
  std::vector<double> spanForces;  ///< the bodies' forces summed over each span of the last pass
  /// The vector width of the pair loops, 4 or 8 doubles, or kPortableLanes (1) for the portable
  /// loops; 0: this processor's (simd_lanes.hpp). With AVX-512, 4 and 8 give bitwise the same
  /// rates; with AVX2 only, both run the 4-wide AVX2 lanes. The portable loops agree with either
  /// to round-off.
  int laneWidth = 0;
  /// Polled between blocks of the first pass, before the pair loop and before each of its chunks
  /// (a pass over millions of particles takes over a second): when set, the rest is skipped and
  /// the rates are not for use.
  Cancellation cancel;
};

/// What the pass that stores the rates also does, so that the particles are not swept once more
/// for it (on W3 each sweep is memory-bound and gains little from a second thread).
struct RateClosing {
  /// s: the integrator's second half kick with the new rates, v += τ (a + g) and ρ += τ dρ/dt for
  /// the fluid, and the boundary particles' ρ set to their extrapolated density (for output);
  /// 0: neither.
  double halfKick = 0;
  /// Out: the fluid's force on each body, Σ m a over its members (N), body b at [b]; every
  /// boundary particle's body must be below its size. Summed over fixed spans of particles, then
  /// the spans in order: the same forces for any thread count. Empty: not summed.
  std::span<std::array<double, 3>> bodyForces;
};

/// Sets every particle's pressure (the boundary particles' extrapolated, with their rhoEst from it),
/// then ax/ay/az (without gravity) and drho (fluid particles), then what `closing` asks for.
RateExtremes computeRates(FluidParticles& p, const NeighbourList& list, const FluidModel& model,
                          RateWorkspace& workspace, const RateClosing& closing = {});

}  // namespace rupture::sph
