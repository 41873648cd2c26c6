#pragma once
// What one rank's sub-domain is made of, cut from the whole sample: copies of its particles (the
// owned ones and their bond ghosts, in the whole sample's order) and of the bonds with an owned
// end, their indices in the whole sample, which particles it owns, what it exchanges with each
// neighbouring rank, and what the contact search needs of the whole sample. Cut where the whole
// sample is (today on every rank; a piece is plain data, so that the first rank alone can cut the
// pieces and send them: docs/distributed.md, "Next").
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "distributed/halo.hpp"

namespace rupture {

struct SubdomainPiece {
  std::size_t wholeSize = 0;             ///< particles of the whole sample
  std::vector<std::int32_t> global;      ///< whole-sample index of each particle (ascending)
  std::vector<std::uint8_t> owned;       ///< 1 for the owned particles, 0 for the bond ghosts
  std::vector<std::int64_t> globalBond;  ///< whole-sample index of each bond (ascending)
  ParticleStore particles;               ///< in the piece's numbering
  BondStore bonds;                       ///< in the piece's numbering, not finalised
  std::vector<Halo::Neighbour> neighbours;   ///< in the piece's numbering
  std::vector<BondStore::CutPair> cutPairs;  ///< pre-cracked pairs with an owned end (whole-sample indices)
  double meanRadius = 0, maxRadius = 0;      ///< of the whole sample's particles (the contact's skin)

  /// The piece of `rank` (owner[k] of each particle, from bisectCoordinates): every particle it
  /// owns or a bond of one reaches, and every bond with an owned end, copied, not the whole sample.
  static SubdomainPiece cut(const BondedSystem& whole, const std::vector<int>& owner, int rank);
};

}  // namespace rupture
