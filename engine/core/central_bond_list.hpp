#pragma once
// The full partner list of central-force bonds, in particle order (core/central_bond_loop.hpp).
// Slot s of particle k is slot s of the bond store's incidence list (same CSR offsets, same
// ascending-bond order), so the per-particle sums are taken in the order of the generic gather.
// Each slot carries copies of what the loop reads about its bond, so the loop streams them
// instead of reading the bond arrays at random: the partner index, the rest length, the
// stiffness, and the effective failure threshold, −inf once the bond is broken (one value for
// "threshold" and "intact": it is written only when the bond breaks).
//
// Two storage forms of (rest length, stiffness, threshold), chosen by build():
// - compact: when the bonds have at most kMaxKinds distinct triples (bit for bit) — a regular
//   lattice has a few hundred: one per bond length and stiffness up to the rounding of the
//   positions — each slot stores a 2-byte index into a table of the triples, entry 0 being the
//   broken bond. 6 bytes a slot instead of 28: the loop is bound by streaming the slots, and the
//   table stays in L1. Lossless: the loop reads the same doubles. Each record also carries
//   1.0 / L0, so that the loop's stretch is a multiplication rather than a division per slot.
// - full: one double per slot for each (random packings, where every bond has its own length).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bond_store.hpp"

namespace rupture {

struct CentralBondList {
  /// What a slot's bond carries, in the compact form: one 32-byte record per distinct triple.
  struct Kind {
    double restLength;     ///< L0 (m)
    double stiffness;      ///< k_b (N/m)
    double limit;          ///< failure threshold, −inf for the broken kind
    double invRestLength;  ///< 1.0 / restLength (1/m), so that the loop multiplies instead of dividing; it
                           ///< also makes the record 32 bytes (one load never straddles two cache lines)
  };
  static constexpr std::size_t kMaxKinds = 65536;  ///< the compact form's index is 16-bit
  static constexpr std::uint16_t kBrokenKind = 0;  ///< kinds[0]: the broken bond

  std::vector<std::int32_t> partner;  ///< the other end of the slot's bond
  bool compact = false;               ///< which form holds the bonds' values (see the file comment)
  // Compact form.
  std::vector<std::uint16_t> kind;  ///< per slot, its index into kinds (kBrokenKind once broken)
  std::vector<Kind> kinds;          ///< the distinct triples, kinds[0] the broken bond
  // Full form.
  std::vector<double> restLength;  ///< L0 (m), the bond's
  std::vector<double> stiffness;   ///< k_b (N/m), the bond's
  std::vector<double> limit;       ///< failureThreshold of the bond while intact, −inf once broken
  /// Per particle x, y, z (m) and the previous s_min, packed by the loop at each evaluation so
  /// that reading a partner touches one cache line instead of four arrays.
  std::vector<double> packed;

  std::size_t size() const { return partner.size(); }

  /// Fills the slots from a finalized bond store (incidence lists, thresholds and intact flags),
  /// in the compact form when allowCompact and the bonds have few enough distinct triples.
  void build(const BondStore& bonds, bool allowCompact = true);
};

}  // namespace rupture
