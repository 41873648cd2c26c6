#pragma once
// The ghosts of a sub-domain and their exchange. A sub-domain holds its owned particles and, as
// ghosts, every particle bonded to one of them that another rank owns (CabanaPD's static halo,
// built once from the reference configuration: bonds only break, so the set never grows). Before
// each force evaluation every ghost gets what a bond law reads of it from its owner: its position,
// its orientation when the law has rotations (beams), and the node's smallest measure of the last
// evaluation (the nodal shift of PMB's compression term). No bond law reads a partner's velocity
// (contact does: its ghosts by distance take velocities, contact_halo.hpp; Silling's damping is not
// decomposed yet), so velocities stay home: 4 doubles a ghost, 8 with rotations. A bond between an owned particle and a
// ghost is then evaluated on both ranks from the same numbers, so both take the same decision in
// the same step and neither needs to tell the other (LAMMPS's `newton_bond off`).
#include <cstdint>
#include <vector>

#include "core/particle_store.hpp"
#include "distributed/communicator.hpp"

namespace rupture {

class Halo {
public:
  /// One neighbouring rank: the local indices of the owned particles it holds as ghosts (sent) and
  /// of the ghosts it owns (received), both in ascending global index, the order both sides agree on.
  struct Neighbour {
    int rank;
    std::vector<std::int32_t> send, receive;
  };

  Halo() = default;
  Halo(Communicator comm, std::vector<Neighbour> neighbours, bool rotations);

  /// Overwrites every ghost's state with its owner's (collective: every rank calls it).
  void refresh(ParticleStore& particles, std::vector<double>& nodalMinimum);

  const std::vector<Neighbour>& neighbours() const { return m_neighbours; }
  /// Doubles sent per ghost and per exchange (4, or 8 with rotations).
  int valuesPerGhost() const { return m_rotations ? 8 : 4; }
  /// Bytes this rank sends per exchange.
  std::size_t bytesSent() const;

private:
  Communicator m_comm = Communicator::world();
  std::vector<Neighbour> m_neighbours;
  bool m_rotations = false;
  std::vector<std::vector<double>> m_sendBuffers, m_receiveBuffers;
};

}  // namespace rupture
