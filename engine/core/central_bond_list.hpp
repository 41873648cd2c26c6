#pragma once
// The full partner list of central-force bonds, in particle order (core/central_bond_loop.hpp).
// Slot s of particle k is slot s of the bond store's incidence list (same CSR offsets, same
// ascending-bond order), so the per-particle sums are taken in the order of the generic gather.
// Each slot carries copies of what the loop reads about its bond, so the loop streams them
// instead of reading the bond arrays at random: the partner index, the rest length, the
// stiffness, and the effective failure threshold, −inf once the bond is broken (one array for
// "threshold" and "intact": it is written only when the bond breaks).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bond_store.hpp"

namespace rupture {

struct CentralBondList {
  std::vector<std::int32_t> partner;  ///< the other end of the slot's bond
  std::vector<double> restLength;     ///< L0 (m), the bond's
  std::vector<double> stiffness;      ///< k_b (N/m), the bond's
  std::vector<double> limit;          ///< failureThreshold of the bond while intact, −inf once broken
  /// Per particle x, y, z (m) and the previous s_min, packed by the loop at each evaluation so
  /// that reading a partner touches one cache line instead of four arrays.
  std::vector<double> packed;

  std::size_t size() const { return partner.size(); }

  /// Fills the slots from a finalized bond store (incidence lists, thresholds and intact flags).
  void build(const BondStore& bonds);
};

}  // namespace rupture
