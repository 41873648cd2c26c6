#include "scenarios/bond_network.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace rupture {

std::vector<double> elementDamage(const BondStore& bonds, std::size_t elementCount,
                                  const std::vector<double>* volume) {
  std::vector<double> initial(elementCount, 0.0), broken(elementCount, 0.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const double lost = bonds.intact[b] > 0.5 ? 0.0 : 1.0;
    const std::int32_t i = bonds.i[b], j = bonds.j[b];
    const double vi = volume ? (*volume)[i] : 1.0, vj = volume ? (*volume)[j] : 1.0;
    initial[i] += vj;  // i's neighbourhood weighs its partner j, and the converse
    initial[j] += vi;
    broken[i] += lost * vj;
    broken[j] += lost * vi;
  }
  for (std::size_t k = 0; k < elementCount; ++k) broken[k] = initial[k] > 0 ? broken[k] / initial[k] : 0.0;
  return broken;
}

std::size_t countFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minSize) {
  std::vector<std::size_t> parent(elementCount), size(elementCount, 1);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto root = [&](std::size_t k) {
    while (parent[k] != k) {
      parent[k] = parent[parent[k]];  // path halving
      k = parent[k];
    }
    return k;
  };
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.intact[b] < 0.5) continue;
    std::size_t a = root(static_cast<std::size_t>(bonds.i[b]));
    std::size_t c = root(static_cast<std::size_t>(bonds.j[b]));
    if (a == c) continue;
    if (size[a] < size[c]) std::swap(a, c);
    parent[c] = a;
    size[a] += size[c];
  }
  std::size_t fragments = 0;
  for (std::size_t k = 0; k < elementCount; ++k)
    if (parent[k] == k && size[k] >= minSize) ++fragments;
  return fragments;
}

}  // namespace rupture
