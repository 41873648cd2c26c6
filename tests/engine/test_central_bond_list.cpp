// The central loop's partner list (core/central_bond_list.hpp): whichever storage form build()
// picks, every slot gives back its bond's partner and exactly (bit for bit) the bond's rest
// length, stiffness and threshold, −inf for a broken bond and NaN for an intact bond whose
// threshold is −inf; the compact form is taken only while the distinct triples fit its 16-bit index.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

#include "core/central_bond_list.hpp"

namespace rupture {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A chain of `n` particles along x at spacing 1e-3 m with bonds to the next and the next but one.
BondStore chain(ParticleStore& p, std::size_t n) {
  p.dimension = 3;
  for (std::size_t k = 0; k < n; ++k) p.add(1e-3 * static_cast<double>(k), 0, 0, 0.5e-3);
  BondStore bonds;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    bonds.add(p, k, k + 1);
    if (k + 2 < n) bonds.add(p, k, k + 2);
  }
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    bonds.stiffness[b] = 1e6 / bonds.restLength[b];
    bonds.threshold[b] = 5e-4;
  }
  return bonds;
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Each slot's values against its bond's, in the form the list holds them.
void expectSlotsMatchBonds(const CentralBondList& list, const BondStore& bonds) {
  ASSERT_EQ(list.size(), bonds.incidence.size());
  for (std::size_t s = 0; s < list.size(); ++s) {
    const std::int32_t e = bonds.incidence[s], b = e >> 1;
    EXPECT_EQ(list.partner[s], (e & 1) ? bonds.i[b] : bonds.j[b]);
    double restLength, stiffness, limit;
    if (list.compact) {
      const CentralBondList::Kind& kind = list.kinds[list.kind[s]];
      restLength = kind.restLength; stiffness = kind.stiffness; limit = kind.limit;
    } else {
      restLength = list.restLength[s]; stiffness = list.stiffness[s]; limit = list.limit[s];
    }
    if (bonds.intact[b] < 0.5) {
      EXPECT_EQ(limit, -kInf);
      if (list.compact) {
        EXPECT_EQ(list.kind[s], CentralBondList::kBrokenKind);
      }
      continue;
    }
    EXPECT_EQ(bits(restLength), bits(bonds.restLength[b]));
    EXPECT_EQ(bits(stiffness), bits(bonds.stiffness[b]));
    if (bonds.failureThreshold[b] == -kInf) {
      EXPECT_TRUE(std::isnan(limit));
    } else {
      EXPECT_EQ(bits(limit), bits(bonds.failureThreshold[b]));
    }
  }
}

TEST(CentralBondList, FewDistinctBondsTakeTheCompactFormWithTheSameValues) {
  ParticleStore p;
  BondStore bonds = chain(p, 200);
  bonds.intact[7] = 0.0;            // broken
  bonds.threshold[11] = -kInf;      // breaks at its first evaluation
  bonds.strength[20] = 2.0;         // its own threshold
  bonds.finalize(p.size());
  CentralBondList list;
  list.build(bonds);
  EXPECT_TRUE(list.compact);
  // One table entry per distinct (L0, k_b, threshold) of the intact bonds, plus the broken entry.
  std::set<std::array<std::uint64_t, 3>> distinct;
  for (std::size_t b = 0; b < bonds.size(); ++b)
    if (bonds.intact[b] > 0.5)
      distinct.insert({bits(bonds.restLength[b]), bits(bonds.stiffness[b]), bits(bonds.failureThreshold[b])});
  EXPECT_EQ(list.kinds.size(), distinct.size() + 1);
  EXPECT_LT(distinct.size(), bonds.size() / 4);  // the chain's bonds repeat: a table, not a copy per bond
  expectSlotsMatchBonds(list, bonds);

  list.build(bonds, false);  // the full form on request
  EXPECT_FALSE(list.compact);
  expectSlotsMatchBonds(list, bonds);
}

TEST(CentralBondList, MoreDistinctBondsThanTheIndexHoldsTakeTheFullForm) {
  ParticleStore p;
  BondStore bonds = chain(p, 40000);  // 79,997 bonds
  for (std::size_t b = 0; b < bonds.size(); ++b) bonds.stiffness[b] *= 1.0 + 1e-9 * static_cast<double>(b);
  bonds.finalize(p.size());
  ASSERT_GT(bonds.size(), CentralBondList::kMaxKinds);
  CentralBondList list;
  list.build(bonds);
  EXPECT_FALSE(list.compact);
  expectSlotsMatchBonds(list, bonds);
}

}  // namespace
}  // namespace rupture
