#pragma once
// A bonded discrete-element system: particles, cohesive beams, contact, and the velocity-Verlet
// step. Scenarios own one, set the prescribed velocities through `prescribe`, and read observables.
#include <cstddef>
#include <functional>
#include <vector>

#include "core/bond_store.hpp"
#include "core/particle_store.hpp"
#include "dem/beam_bond.hpp"
#include "dem/hertz_contact.hpp"

namespace rupture {

class BondedSystem {
public:
  ParticleStore particles;
  BondStore bonds;
  BeamParameters beam;
  HertzContact contact;

  /// Sets the velocity of the prescribed degrees of freedom (FixedDof) at time t; called before
  /// each drift (t = mid-step) and after each step (t = end of step).
  std::function<void(ParticleStore&, double t)> prescribe;

  /// Cundall local damping coefficient γ in [0, 1) (0: none). Only for quasi-static runs.
  double localDamping = 0.0;

  double time = 0.0;          ///< s
  std::size_t steps = 0;
  std::size_t brokenLastStep = 0;

  /// Prepares the per-step arrays and evaluates the loads at t = 0. Call once the sample is built.
  void initialize();

  /// One velocity-Verlet step of length dt (translation and rotation).
  void step(double dt);

  /// Gershgorin bound of the bonds' critical step (physics-reference §1.8):
  /// min over particles of min(√(m / Σ k_tr), √(I / Σ k_rot)),
  /// k_tr = max(E S/L0, 12 E I/L0³), k_rot = max(G J/L0, 4 E I/L0).
  double criticalTimeStep() const;

  double kineticEnergy() const;  ///< translational + rotational (J)
  double elasticEnergy() const;  ///< beams + contacts (J)

private:
  void computeLoads();
  void handOverBrokenBonds();
  void kick(double halfDt);
  void drift(double dt);
  std::vector<std::uint8_t> m_wasIntact;
};

}  // namespace rupture
