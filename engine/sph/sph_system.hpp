#pragma once
// One weakly compressible SPH fluid with its rigid boundary bodies, and the time integrator.
// The step is a kick–drift–kick leapfrog with one pair-loop evaluation per step (the scheme of
// LAMMPS' fix sph): half kick of v and ρ, drift of x, estimates of v and ρ at the end of the step
// for the pair loop, then the second half kick with the new rates. Boundary particles move with
// their body; their density is not integrated but extrapolated from the fluid (fluid_rates.hpp).
#include <array>
#include <cstddef>
#include <vector>

#include "core/cancellation.hpp"
#include "sph/fluid_model.hpp"
#include "sph/fluid_particles.hpp"
#include "sph/fluid_rates.hpp"
#include "sph/neighbour_list.hpp"
#include "sph/relative_displacement.hpp"
#include "sph/rigid_body.hpp"

namespace rupture::sph {

class SphSystem {
public:
  FluidModel model;
  FluidParticles particles;
  std::vector<RigidBody> bodies;
  double time = 0;         ///< s
  std::size_t steps = 0;
  /// Neighbour-list skin as a fraction of the kernel support. 0.08 rather than 0.1: W3 on one
  /// thread took 10 % less processor time at 300 steps and at 1000 under the half-skin rebuild
  /// rule (more builds, but fewer listed pairs every step); under the relative-displacement rule
  /// 0.06, 0.10 and 0.12 were not distinguishable from it (bench/README.md).
  double skinFraction = 0.08;
  int sortEvery = 4;          ///< re-sort particles in cell order every this many list builds
  /// Polled between the passes of a list build and of initialise() (each well under a second at
  /// millions of particles): a set flag throws RunCancelled, after which the system is not for use.
  Cancellation cancel;

  /// Builds the neighbour lists and the rates at t = 0. Call once particles and bodies are set.
  void initialise();
  /// Advances by dt (s).
  void step(double dt);

  /// Everything a step changes (docs/checkpoints.md): the particles in their current order, the
  /// bodies' motion, the clock, the rates' extremes and the list's reference positions. Loading
  /// rebuilds the neighbour list at those positions, as it was built, rather than storing it.
  void exchangeState(StateArchive& archive);

  /// Monaghan & Kos (1999) time step from the last rates (docs/references.md#eq-sph):
  /// dt = C min(min_a √(h/|f_a|), h/(c_max + max_ab |μ_ab|)).
  double stableTimeStep(double courant) const;
  const RateExtremes& extremes() const { return m_extremes; }
  std::size_t listBuilds() const { return m_builds; }
  const NeighbourList& neighbourList() const { return m_list; }

  // Diagnostics over fluid particles (SI; per metre of depth in 2D).
  double fluidMass() const;
  double kineticEnergy() const;
  double potentialEnergy() const;  ///< −Σ m g·x, zero at the origin
  std::array<double, 3> fluidMomentum() const;
  /// Pressure at a point: Shepard average Σ p_b W V_b / Σ W V_b over fluid within the support
  /// (Pa); 0 where no fluid is within the support (a dry point reads the ambient pressure).
  double probePressure(double px, double py, double pz) const;

private:
  void rebuildLists();
  double listSkin() const { return model.kernel().support() * skinFraction; }  ///< cutoff − support (m)
  void refreshMembers();
  /// The rates at the current state, the bodies' forces from them and their impulses over the
  /// step (halfKick × (old + new force)), and halfKick (s) as RateClosing::halfKick.
  void evaluateRates(double halfKick);
  /// Sets the members' velocities from their body's speed; fixedToo: also those of fixed bodies
  /// (their zero velocities never change after initialise).
  void setBodyVelocities(bool fixedToo);

  NeighbourList m_list;
  RelativeDisplacementBound m_relativeMove;
  RateWorkspace m_workspace;
  RateExtremes m_extremes;
  std::vector<std::array<double, 3>> m_forces;      ///< evaluateRates' scratch: the bodies' forces (N)
  ParticleArray<double> m_x0, m_y0, m_z0;           // the positions at the last list build (m)
  ParticleArray<double> m_permuteScratch;           // FluidParticles::permute's, kept between re-sorts
  ParticleArray<std::int32_t> m_permuteIndexScratch;
  std::size_t m_builds = 0;
  double m_skinBudget = 0;  ///< m: what interacting pairs may still close in before a rebuild (step 3)
};

}  // namespace rupture::sph
