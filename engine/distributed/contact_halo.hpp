#pragma once
// The ghosts of a sub-domain's contact: every particle of another rank that could touch one of its
// owned particles before the contact list is next rebuilt. Unlike the bond ghosts (halo.hpp), fixed
// by the reference configuration, these follow the motion (fragments fly), so they are chosen
// again at every rebuild of the contact list, which every rank takes at once: each rank sends the
// others' owned bounding boxes the particles of its own within reach of them (LAMMPS's ghost atoms
// within the cutoff plus the skin, chosen by distance), and the receivers append those they do not
// hold yet after their bonded particles. Between rebuilds, each step sends the same ghosts' positions
// and velocities (contact reads the partner's velocity and spin: 9 doubles a ghost).
//
// Ownership stays with the partition of the reference configuration (no migration): a fragment
// that flies away stays its rank's, and that rank's bounding box grows with it, so the choice stays
// exact and only its cost grows (docs/distributed.md).
#include <cstdint>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "distributed/communicator.hpp"
#include "dem/hertz_contact.hpp"
#include "rupture/state_archive.hpp"

namespace rupture {

class ContactHalo : public ContactDomain {
public:
  /// system: the sub-domain's, whose first `global.size()` particles are its owned particles and
  /// bond ghosts (global: their whole-sample indices, ascending; owned: 1 for the owned ones).
  /// cutPairs: the whole sample's pre-cracked pairs (whole-sample indices) with an owned end.
  /// meanRadius, maxRadius: of the whole sample. `system` must outlive this and stay in place.
  ContactHalo(Communicator comm, BondedSystem& system, std::vector<std::int32_t> global, std::vector<std::uint8_t> owned,
              std::vector<BondStore::CutPair> cutPairs, double meanRadius, double maxRadius);

  const std::vector<std::uint8_t>& evaluated() const override { return m_evaluated; }
  const std::vector<std::int32_t>& wholeIndex() const override { return m_wholeIndex; }
  double largestOverRanks(double value) const override { return m_comm.max(value); }
  double wholeMeanRadius() const override { return m_meanRadius; }
  double wholeMaxRadius() const override { return m_maxRadius; }
  void gatherCandidates(double skin, double maxRadius) override;

  /// Overwrites every contact ghost's position and velocities with its owner's (collective; every
  /// step, before the force evaluation).
  void refresh(ParticleStore& p);

  /// Contact ghosts held now (appended or among the bond ghosts) and the bytes a step sends.
  std::size_t ghostCount() const;
  std::size_t bytesSent() const;

  /// The ghosts by distance and who sends what: saved with a rank's checkpoint, and loaded before
  /// the sub-domain's system, whose particle count they set.
  void exchangeState(StateArchive& archive);

private:
  std::int32_t baseLocalOf(std::int32_t global) const;
  void adoptGhosts(const std::vector<std::int32_t>& appended);  ///< sets the indices, the local cut pairs and the buffers

  Communicator m_comm;
  BondedSystem* m_system;
  std::size_t m_base;                      // particles the bonds know (owned and bond ghosts)
  std::vector<std::int32_t> m_baseGlobal;  // their whole-sample indices, ascending
  std::vector<std::uint8_t> m_baseOwned;
  std::vector<BondStore::CutPair> m_cutPairs;  // whole-sample indices
  double m_meanRadius, m_maxRadius;

  std::vector<std::uint8_t> m_evaluated;   // per local particle (owned, bond ghosts, ghosts by distance)
  std::vector<std::int32_t> m_wholeIndex;  // per local particle
  // Per rank: local indices of the owned particles sent to it, and of the ghosts received from it,
  // each in the order the sender chose them (its ascending local order, the whole sample's).
  std::vector<std::vector<std::int32_t>> m_send, m_receive;
  std::vector<std::vector<double>> m_sendBuffers, m_receiveBuffers;
};

}  // namespace rupture
