#pragma once
// Contiguous bond arrays (structure of arrays). A bond joins particle indices i < j and keeps its
// reference state: rest length L0 and unit direction n0 (i -> j) at creation. Orientations are the
// identity when bonds are created, so the body-frame tangent of both ends is n0 itself.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/particle_store.hpp"

namespace rupture {

struct BondStore {
  std::vector<std::int32_t> i, j;
  std::vector<double> restLength;      ///< L0 (m)
  std::vector<double> n0x, n0y, n0z;   ///< reference direction i -> j
  /// The bond's integrity: 1 intact, 0 broken, in between partly damaged (anisotropic damage); a
  /// factor on its loads, so the kernel has no branch.
  std::vector<double> intact;

  // Set once from the material (samples/material_assignment.cpp) and the microstructure; carried by remap.
  /// The bond's own stiffness: central laws' normal stiffness k (N/m); for beams, whose stiffness
  /// follows the (calibrated) beam parameters, the factor on E_μ (1). 1 until the material sets it.
  std::vector<double> stiffness;
  std::vector<double> threshold;       ///< failure threshold, in the criterion's unit (+inf: unbreakable)
  std::vector<double> strength;        ///< factor on the threshold (1; +inf: never breaks), e.g. regions

  // Written by the force kernel: force on j (force on i is its opposite), torques on i, j, and the
  // failure measure. The central-force loop (core/central_bond_loop.hpp) does not store them each
  // step; read them through BondedSystem::bondLoads(), which fills them on demand through a const
  // system (hence mutable: a cache of the current configuration's loads).
  mutable std::vector<double> fjx, fjy, fjz;
  std::vector<double> tix, tiy, tiz;
  std::vector<double> tjx, tjy, tjz;
  /// Anisotropic damage (damage/anisotropic_damage.hpp): the bond as a bundle of up to three fibres,
  /// in the order they fail. Fibre c fails once the failure measure reaches fibreFactor[c] times the
  /// effective threshold, leaving the bond the integrity fibreIntegrity[c] (non-increasing in c; the
  /// last fibre leaves 0; unused fibres have factor +inf). Set by the material after the bonds are
  /// final; empty (the default): one fibre, the isotropic criterion.
  std::array<std::vector<double>, 3> fibreFactor, fibreIntegrity;
  bool hasFibres() const { return !fibreFactor[0].empty(); }
  /// The factor on bond b's threshold at which it first loses integrity: its first fibre that
  /// carries something (1 without fibres; +inf if none does).
  double firstDamageFactor(std::size_t b) const;

  mutable std::vector<double> failureMeasure;  ///< the criterion's measure at the last evaluation (its unit)
  std::vector<double> failureThreshold;  ///< threshold × strength, refreshed by finalize (criterion's unit)

  // Particle -> bond incidence (CSR), built once after the bonds: entries are 2·b + end (0: i, 1: j).
  std::vector<std::int32_t> incidenceStart, incidence;

  /// A pair whose bond a pre-crack removed (samples/notches.hpp), with the bond's rest length: contact
  /// touches it at min(R_i + R_j, L0), as a broken bond, so pairs packed overlapping across a notch
  /// are not pushed apart at the first step. Carried by remap.
  struct CutPair {
    std::int32_t i, j;
    double restLength;  ///< m
  };
  std::vector<CutPair> cutPairs;

  std::size_t size() const { return i.size(); }

  /// Adds a bond between particles a and b in their current configuration (rest state).
  std::size_t add(const ParticleStore& particles, std::size_t a, std::size_t b);

  /// Sizes the per-step outputs, the effective thresholds and the incidence lists; call after the
  /// last add() and after any change of threshold or strength.
  void finalize(std::size_t particleCount);

  /// Renumbers particle indices after ParticleStore::compact and drops bonds (and cut pairs) touching
  /// removed particles.
  void remap(const std::vector<std::int32_t>& newIndex);

  /// Renumbers particle indices after ParticleStore::permute (newIndex: old -> new, a permutation):
  /// each bond keeps i < j, taking the opposite reference direction when its ends swap, and the
  /// bonds are sorted by (i, j). Call before finalize.
  void renumber(const std::vector<std::int32_t>& newIndex);

  /// The bonds with keep[b] != 0 whose two ends newIndex keeps (ParticleStore::subset's numbering:
  /// old -> new, -1 if removed), renumbered, in order, with their reference state, and the cut
  /// pairs whose two ends it keeps; this store is unchanged. Call finalize on the result.
  BondStore subset(const std::vector<std::uint8_t>& keep, const std::vector<std::int32_t>& newIndex) const;

  /// Keeps only the bonds with keep[b] != 0, in order (call before finalize).
  void filter(const std::vector<std::uint8_t>& keep);

  std::size_t intactCount() const;

  /// What a run changes: the intact flags and the loads of the last evaluation (the torques only
  /// with `torques`: laws without them never write them). Stiffness and thresholds are the set-up's.
  void exchangeState(StateArchive& archive, bool torques);

  /// Number of intact bonds per particle.
  std::vector<int> coordination(std::size_t particleCount) const;

  /// Calls f on every per-bond reference array of s (all but i and j), a store or a const store,
  /// the fibres' arrays with `fibres`: the one list that moveBond, truncate, renumber, subset and a
  /// sub-domain's transfer share.
  template <class Store, class F>
  static void forEachReferenceArrayOf(Store& s, bool fibres, F&& f) {
    for (auto* v : {&s.restLength, &s.n0x, &s.n0y, &s.n0z, &s.intact, &s.stiffness, &s.threshold, &s.strength}) f(*v);
    if (fibres)
      for (std::size_t c = 0; c < s.fibreFactor.size(); ++c) {
        f(s.fibreFactor[c]);
        f(s.fibreIntegrity[c]);
      }
  }

private:
  /// Copies bond `from`'s reference state (all but i, j) onto slot `to` (to <= from), for remap/filter.
  void moveBond(std::size_t from, std::size_t to);
  /// Keeps the first m bonds of every reference array.
  void truncate(std::size_t m);
  /// Calls f on every per-bond reference array but i and j: the one list moveBond, truncate and
  /// renumber share.
  template <class F>
  void forEachReferenceArray(F&& f) {
    forEachReferenceArrayOf(*this, hasFibres(), f);
  }
};

}  // namespace rupture
