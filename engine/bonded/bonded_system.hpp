#pragma once
// A bonded particle system: particles, bonds with their material model (a bond law and a failure
// criterion: beams, lattice springs, peridynamic bonds), contact between unbonded pairs, and the
// velocity-Verlet step. Scenarios own one, set the prescribed velocities through `prescribe`, and
// read observables.
#include <cstddef>
#include <functional>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/bond_store.hpp"
#include "core/central_bond_list.hpp"
#include "core/particle_store.hpp"
#include "dem/beam_bond.hpp"
#include "bonded/bond_model.hpp"
#include "dem/hertz_contact.hpp"

namespace rupture {

class BondedSystem {
public:
  ParticleStore particles;
  BondStore bonds;
  BondModel model;      ///< law + criterion; per-bond constants live in `bonds` (stiffness, threshold)
  BeamParameters beam;  ///< parameters of the beam law, read when `model` is a BeamModel
  HertzContact contact;

  /// Sets the velocity of the prescribed degrees of freedom (FixedDof) at time t; called before
  /// each drift (t = mid-step) and after each step (t = end of step).
  std::function<void(ParticleStore&, double t)> prescribe;

  /// Adds external loads (body forces, indenters, projectiles) at time t, after the bonds and
  /// contacts have set the particle forces; called at every force evaluation.
  std::function<void(ParticleStore&, double t)> externalLoads;

  /// Overwrites the ghost particles' state with their owners' before each force evaluation (after
  /// the drift; in initialize, before the first): set by a decomposed run (distributed/subdomain.hpp),
  /// empty on one rank. nodalMinimum: each node's smallest failure measure of the last evaluation
  /// (the nodal shift's s_min), which ghosts take from their owners too.
  std::function<void(ParticleStore&, std::vector<double>& nodalMinimum)> refreshGhosts;

  /// Cundall local damping coefficient γ in [0, 1) (0: none). Only for quasi-static runs.
  double localDamping = 0.0;

  /// Silling's local damping of bonds around damage (core/local_damping.hpp; material.local_damping):
  /// coefficient d (1; 0: none) and the bar wave speed v0 = √(E/ρ) it is scaled by (m/s).
  double bondDamping = 0.0;
  double dampingWaveSpeed = 0.0;

  /// Central-force laws without bond damping run the particle-order loop
  /// (core/central_bond_loop.hpp); false runs the generic bond loop for every law, with the same
  /// result bit for bit (kept for comparisons: tests, benchmarks).
  bool centralLoop = true;
  /// The central loop's partner list in its compact form (a table of the distinct bond values,
  /// core/central_bond_list.hpp) when the bonds allow it; false forces the full form (tests).
  bool compactCentralList = true;

  double time = 0.0;          ///< s
  std::size_t steps = 0;
  std::size_t brokenLastStep = 0;
  /// The bonds that broke in the last force evaluation (brokenLastStep of them), in bond order.
  const std::vector<std::size_t>& bondsBrokenLastStep() const { return m_brokenNow; }

  /// A system with this one's model, parameters, callbacks and clock, and no particles, bonds or
  /// contacts (its contact's parameters only): the start of a sub-domain, which takes its own
  /// particles and bonds (distributed/subdomain.hpp) without a copy of the whole sample. Call
  /// initialize on it once it has them.
  BondedSystem withoutElements() const;

  /// Prepares the per-step arrays and evaluates the loads at t = 0. Call once the sample is built.
  void initialize();

  /// Everything a step changes (docs/checkpoints.md): particles, bonds, contacts, the damage index,
  /// the clock (the central loop's list is rebuilt from the bonds). The set-up (sample, model,
  /// prescriptions) is rebuilt first.
  void exchangeState(StateArchive& archive);

  /// Takes the particles' and bonds' state a decomposed run gathered into this whole system from
  /// its ranks (distributed/subdomain.hpp), at `time` after `steps` steps: the per-bond loads are
  /// evaluated again when next read (bondLoads). The system is not stepped itself.
  void adoptGatheredState(double atTime, std::size_t atSteps);

  /// Grows or shrinks the particles to n, keeping the first `bondedCount` (every particle a bond
  /// names): a sub-domain's ghosts by distance (distributed/contact_halo.hpp) come and go after
  /// them, without bonds; their per-particle arrays follow (zero, identity orientation).
  void setParticleCount(std::size_t n, std::size_t bondedCount);

  /// One velocity-Verlet step of length dt (translation and rotation).
  void step(double dt);

  /// Gershgorin bound of the bonds' critical step: min over particles of
  /// min(√(m / Σ k_tr), √(I / Σ k_rot)) with each law's k_tr, k_rot (docs/references.md#eq-gershgorin);
  /// central-force laws use the full Gershgorin row, √(2m / Σ k) (the PD bound of Silling & Askari 2005).
  double criticalTimeStep() const;

  double kineticEnergy() const;  ///< translational + rotational (J)
  double elasticEnergy() const;  ///< bonds + contacts (J)
  double bondEnergy() const;     ///< intact bonds only (J)

  /// Each bond's translational stiffness (N/m), for affine wave-speed estimates.
  std::vector<double> bondStiffness() const;

  /// Largest failure measure over threshold among intact bonds (0 if all are unbreakable). It grows
  /// about linearly with the load before the first break: runs use it to estimate their progress.
  double maxFailureRatio() const;

  /// The bond store with its per-bond loads (fjx, fjy, fjz: force on j; failureMeasure) of the
  /// current configuration. The central-force loop does not store them each step: this evaluates
  /// them when they are stale. Read loads through it, not through `bonds` directly.
  const BondStore& bondLoads() const;

  /// Damage index φ of each particle (PeriLab's damage index; docs/references.md#eq-pd) over its
  /// initial bonds, φ = Σ (1 − integrity) V_partner / Σ V_partner (a broken bond counts 1, a partly
  /// damaged one its lost part); kept up to date as bonds break (O(damaged bonds) per step).
  const std::vector<double>& damageIndex() const { return m_damage; }

  /// True when the system moves in the x-y plane (set by initialize): dimension 2, every particle
  /// at the same z, every orientation a rotation about z, no velocity out of the plane
  /// (v_z = ω_x = ω_y = 0) and every bond's reference direction in the plane. The step then runs the planar forms of the bond loop, kick and drift (only x, y and
  /// the rotation about z move; v_z, ω_x, ω_y are not integrated: in 2D their loads are 0).
  bool planarMotion() const { return m_planar; }

  /// Calls f(law, criterion) with the model's concrete types (the beam law filled from `beam`).
  template <class F>
  decltype(auto) visitModel(F&& f) const {
    return std::visit(
        [&](const auto& m) -> decltype(auto) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, BeamModel>) return f(BeamLaw{beam}, m.criterion);
          else return f(m.law, m.criterion);
        },
        model);
  }

private:
  void computeLoads();
  /// Records the bonds whose integrity dropped in the last evaluation (damage index, contact
  /// hand-over of those that broke); returns how many broke.
  std::size_t handOverDamagedBonds();
  std::size_t recordDamagedBonds(const std::vector<std::size_t>& damaged);
  void kick(double halfDt);
  void drift(double dt);
  double partnerVolume(std::int32_t particle) const;  ///< V (m³), or 1 without volumes
  void recordDamage(std::size_t bond, double lost);  ///< adds a bond's lost integrity to its ends' φ
  std::vector<double> m_recordedIntegrity;           ///< each bond's integrity as φ counts it
  std::vector<double> m_damage, m_brokenVolume, m_bondedVolume;  ///< φ = broken / bonded partner volume
  std::vector<double> m_previousLength;  ///< bond lengths at the last evaluation, for the damping
  double m_step = 0.0;                   ///< Δt of the step being taken (0 before the first)
  std::vector<double> m_minStretch;      ///< per node, for criteria with a nodal shift (LAMMPS's α)
  std::vector<double> m_minStretchNext;  ///< the central loop's write buffer, swapped after each pass
  double m_loadTime = 0.0;  ///< time of the configuration the loads are evaluated on
  CentralBondList m_central;            ///< full partner list of the central-force loop
  bool m_centralCurrent = false;        ///< m_central agrees with bonds (no other loop ran since it was built)
  mutable bool m_loadsStale = false;    ///< bonds.fjx/failureMeasure are older than the last evaluation
  std::vector<std::size_t> m_broken;    ///< bonds damaged in the last evaluation (central loop)
  std::vector<std::size_t> m_brokenNow; ///< bonds broken in the last evaluation
  bool m_planar = false;                ///< see planarMotion()
};

}  // namespace rupture
