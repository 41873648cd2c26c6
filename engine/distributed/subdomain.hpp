#pragma once
// One rank's part of a decomposed bonded run: a BondedSystem of its owned particles and their
// ghosts (distributed/halo.hpp), numbered in the order of the whole sample, with the bonds that
// have an owned end. Each owned particle keeps all its bonds in the whole sample's order, so its
// force is the same sum in the same order as on one rank: the owned particles' trajectories are
// the one-rank trajectories bit for bit, for any rank count and any partition. Reductions over
// particles (energies, momentum) sum each rank's share and then the ranks: round-off apart from
// the one-rank sum.
//
// Contact between fragments takes a second set of ghosts, chosen by distance at each rebuild of the
// contact list (contact_halo.hpp), appended after the particles the bonds know.
//
// Set up on every rank from the same whole sample (every rank builds it: the sample builders are
// deterministic) and cut from it without a copy of it; only the first rank keeps the whole, into
// which the outputs are gathered. What the decomposition does not carry yet, it
// refuses by name: Silling's bond damping (it reads the partners' damage index).
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "distributed/communicator.hpp"
#include "distributed/contact_halo.hpp"
#include "distributed/halo.hpp"
#include "distributed/subdomain_piece.hpp"
#include "rupture/state_archive.hpp"

namespace rupture {

class Subdomain {
public:
  /// Keeps the particles of `whole` owned by comm.rank() (owner[k], from bisectCoordinates) and
  /// their ghosts. `whole` is set up (sample, material, velocities, fixed degrees of freedom),
  /// initialised or not; the sub-domain's system is not: set its `prescribe` and `externalLoads` in
  /// local indices (globalIndex, localOf) and call system.initialize() on every rank.
  Subdomain(const BondedSystem& whole, const std::vector<int>& owner, Communicator comm);
  /// The same from this rank's piece (SubdomainPiece::cut, or scatterSubdomainPieces where only the
  /// first rank built the sample) and the whole system's configuration (BondedSystem::withoutElements,
  /// or broadcastConfiguration).
  Subdomain(BondedSystem configuration, SubdomainPiece piece, Communicator comm);
  // The contact's ghosts refer to `system` in place.
  Subdomain(const Subdomain&) = delete;
  Subdomain& operator=(const Subdomain&) = delete;

  /// Its particles: the owned ones and the bond ghosts, in the whole sample's order (globalIndex),
  /// then, with contact, the ghosts by distance of the last rebuild of the contact list.
  BondedSystem system;

  std::size_t wholeSize() const { return m_wholeSize; }
  /// Global index of each owned particle and bond ghost (ascending; the ghosts by distance follow them).
  const std::vector<std::int32_t>& globalIndex() const { return m_global; }
  /// Local index of a global particle, -1 when this rank holds it neither as owned nor as ghost.
  std::int32_t localOf(std::int32_t global) const;
  /// The members of a particle set (whole-sample indices) this rank holds, in its numbering, in
  /// the set's order: a loaded face or region, for a prescription on the sub-domain.
  std::vector<std::int32_t> localMembers(const std::vector<std::int32_t>& members) const;
  bool owns(std::size_t local) const { return local < m_owned.size() && m_owned[local] != 0; }
  std::size_t ownedCount() const { return m_ownedCount; }
  const Halo& halo() const { return *m_halo; }
  /// The contact's ghosts by distance; nullptr without contact.
  const ContactHalo* contactHalo() const { return m_contactHalo.get(); }
  const Communicator& communicator() const { return m_comm; }

  /// A per-particle field of the owned particles, in the whole sample's order, on every rank.
  std::vector<double> gather(const std::vector<double>& local) const;
  /// Σ over the owned particles of f(local index), summed over the ranks.
  template <class F>
  double sumOwned(F&& f) const {
    double s = 0;
    for (std::size_t k = 0; k < m_owned.size(); ++k)
      if (m_owned[k]) s += f(k);
    return m_comm.sum(s);
  }
  /// Writes every rank's owned particles (kinematics and orientations) and the bonds whose end i it
  /// owns and whose integrity changed since the last gather into `whole` on the first rank (the
  /// sample this sub-domain was cut from), which then reads as the one-process system would at this
  /// step (BondedSystem::adoptGatheredState). With contact, `whole` takes the contact energy of the
  /// ranks, summed in the one-process order. The other ranks only send: their `whole` is not read
  /// or written, and may hold no elements (BondedSystem::withoutElements). Collective. Scenarios
  /// call it before each output, which the first rank alone computes on `whole` and writes.
  void gatherInto(BondedSystem& whole) const;
  /// Only the bonds' part of gatherInto: the integrity of the bonds that changed since the last
  /// gather (for a connectivity check between outputs; the kinematics are not sent). Collective.
  void gatherBondsInto(BondedSystem& whole) const;

  /// Σ of per-particle terms (three each: terms[3t..3t+2] of the owned particle with global index
  /// ids[t]) over every rank, added in the whole sample's order from 0: the sum one process takes
  /// over its particles in index order, bit for bit (an external body's reaction). Collective.
  std::array<double, 3> sumInWholeOrder(const std::vector<std::int64_t>& ids, const std::vector<double>& terms) const;

  /// Saves or loads the sub-domain's state (its system, and what the whole system last took from
  /// it): a rank's checkpoint (docs/checkpoints.md).
  void exchangeState(StateArchive& archive);
  /// Bonds broken so far in the whole sample (each counted once: by the owner of its end i).
  std::uint64_t brokenBonds() const;
  /// Of the bonds that broke in the last step, those this rank counts (it owns their end i): their
  /// sum over the ranks is the whole sample's count. Not collective.
  std::uint64_t brokenLastStepHere() const;
  /// Translational and rotational kinetic energy of the whole sample (J).
  double kineticEnergy() const;

private:
  Communicator m_comm;
  std::size_t m_wholeSize = 0, m_ownedCount = 0;
  std::vector<std::int32_t> m_global;
  std::vector<std::uint8_t> m_owned;
  std::vector<std::int64_t> m_globalBond;  // each local bond's index in the whole sample
  // Each local bond's integrity as the whole system last took it: a gather sends only the bonds
  // that changed since (bonds are many, and few break between two outputs).
  mutable std::vector<double> m_gatheredIntact;
  std::shared_ptr<Halo> m_halo;  // shared with system.refreshGhosts
  std::shared_ptr<ContactHalo> m_contactHalo;  // shared with system.contact and system.refreshGhosts
};

}  // namespace rupture
