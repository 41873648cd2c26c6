#include "core/central_bond_list.hpp"

#include <array>
#include <bit>
#include <limits>
#include <unordered_map>

#include "core/parallel.hpp"

namespace rupture {

namespace {

constexpr double kBroken = -std::numeric_limits<double>::infinity();

// The threshold a slot carries: an intact bond whose threshold is itself −inf breaks at its first
// evaluation; NaN does that (no measure is below it) without being mistaken for the broken mark.
double slotLimit(const BondStore& bonds, std::size_t b) {
  if (bonds.intact[b] <= 0.0) return kBroken;
  return bonds.failureThreshold[b] == kBroken ? std::numeric_limits<double>::quiet_NaN() : bonds.failureThreshold[b];
}

using Triple = std::array<std::uint64_t, 3>;  // the bits of (L0, k_b, threshold)

struct TripleHash {
  std::size_t operator()(const Triple& t) const {
    std::uint64_t h = t[0] * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29) ^ t[1]) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 31) ^ t[2]) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

// Each bond's kind index, or an empty vector when there are more than kMaxKinds kinds. Bit
// patterns, not values, identify a kind, so the table gives back exactly the stored doubles.
std::vector<std::uint16_t> bondKinds(const BondStore& bonds, std::vector<CentralBondList::Kind>& kinds) {
  kinds.assign(1, CentralBondList::Kind{1.0, 0.0, kBroken, 1.0});
  std::unordered_map<Triple, std::uint16_t, TripleHash> index;
  std::vector<std::uint16_t> kindOf(bonds.size());
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const double limit = slotLimit(bonds, b);
    if (limit == kBroken) {
      kindOf[b] = CentralBondList::kBrokenKind;
      continue;
    }
    const Triple key{std::bit_cast<std::uint64_t>(bonds.restLength[b]), std::bit_cast<std::uint64_t>(bonds.stiffness[b]),
                     std::bit_cast<std::uint64_t>(limit)};
    auto [it, added] = index.try_emplace(key, static_cast<std::uint16_t>(kinds.size()));
    if (added) {
      if (kinds.size() == CentralBondList::kMaxKinds) return {};
      kinds.push_back({bonds.restLength[b], bonds.stiffness[b], limit, 1.0 / bonds.restLength[b]});
    }
    kindOf[b] = it->second;
  }
  return kindOf;
}

}  // namespace

void CentralBondList::build(const BondStore& bonds, bool allowCompact) {
  const std::size_t n = bonds.incidence.size();
  const std::ptrdiff_t slots = static_cast<std::ptrdiff_t>(n);
  partner.resize(n);
  std::vector<std::uint16_t> kindOf;
  if (allowCompact) kindOf = bondKinds(bonds, kinds);
  compact = allowCompact && kindOf.size() == bonds.size();
  if (compact) {
    kind.resize(n);
    restLength.clear(); stiffness.clear(); limit.clear();
  } else {
    kind.clear(); kinds.clear();
    restLength.resize(n); stiffness.resize(n); limit.resize(n);
  }
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::ptrdiff_t s = 0; s < slots; ++s) {
    const std::int32_t e = bonds.incidence[s], b = e >> 1;
    partner[s] = (e & 1) ? bonds.i[b] : bonds.j[b];
    if (compact) {
      kind[s] = kindOf[b];
    } else {
      restLength[s] = bonds.restLength[b];
      stiffness[s] = bonds.stiffness[b];
      limit[s] = slotLimit(bonds, b);
    }
  }
}

}  // namespace rupture
