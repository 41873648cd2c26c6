#include "core/central_bond_list.hpp"

#include <limits>

#include "core/parallel.hpp"

namespace rupture {

void CentralBondList::build(const BondStore& bonds) {
  const std::size_t n = bonds.incidence.size();
  partner.resize(n);
  restLength.resize(n);
  stiffness.resize(n);
  limit.resize(n);
  const std::ptrdiff_t slots = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::ptrdiff_t s = 0; s < slots; ++s) {
    const std::int32_t e = bonds.incidence[s], b = e >> 1;
    partner[s] = (e & 1) ? bonds.i[b] : bonds.j[b];
    restLength[s] = bonds.restLength[b];
    stiffness[s] = bonds.stiffness[b];
    constexpr double kBroken = -std::numeric_limits<double>::infinity();
    // An intact bond whose threshold is itself −inf breaks at its first evaluation: NaN does that
    // (no measure is below it) without being mistaken for the broken mark.
    const double threshold = bonds.failureThreshold[b] == kBroken ? std::numeric_limits<double>::quiet_NaN()
                                                                  : bonds.failureThreshold[b];
    limit[s] = bonds.intact[b] > 0.5 ? threshold : kBroken;
  }
}

}  // namespace rupture
