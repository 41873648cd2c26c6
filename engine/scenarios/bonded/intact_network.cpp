#include "scenarios/bonded/intact_network.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace rupture {

std::vector<double> elementDamage(const BondStore& bonds, std::size_t elementCount,
                                  const std::vector<double>* volume) {
  std::vector<double> initial(elementCount, 0.0), broken(elementCount, 0.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const double lost = 1.0 - bonds.intact[b];  // a partly damaged bond (anisotropic damage) in part
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

BondComponents::BondComponents(const BondStore& bonds, std::size_t elementCount)
    : m_parent(elementCount), m_size(elementCount, 1) {
  std::iota(m_parent.begin(), m_parent.end(), std::size_t{0});
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.intact[b] <= 0.0) continue;
    std::size_t a = root(static_cast<std::size_t>(bonds.i[b]));
    std::size_t c = root(static_cast<std::size_t>(bonds.j[b]));
    if (a == c) continue;
    if (m_size[a] < m_size[c]) std::swap(a, c);
    m_parent[c] = a;
    m_size[a] += m_size[c];
  }
}

std::size_t BondComponents::root(std::size_t k) {
  while (m_parent[k] != k) {
    m_parent[k] = m_parent[m_parent[k]];  // path halving
    k = m_parent[k];
  }
  return k;
}

bool groupsConnected(const BondStore& bonds, std::size_t elementCount, const std::vector<std::int32_t>& a,
                     const std::vector<std::int32_t>& b) {
  BondComponents components(bonds, elementCount);
  std::vector<std::size_t> roots;
  roots.reserve(a.size());
  for (std::int32_t k : a) roots.push_back(components.root(static_cast<std::size_t>(k)));
  std::sort(roots.begin(), roots.end());
  for (std::int32_t k : b)
    if (std::binary_search(roots.begin(), roots.end(), components.root(static_cast<std::size_t>(k)))) return true;
  return false;
}

FragmentAnalysis analyseFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minFragmentSize) {
  BondComponents components(bonds, elementCount);
  FragmentAnalysis out;
  out.elementFragment.assign(elementCount, -1);
  // Fragments by decreasing size (ties by representative, so the numbering is reproducible).
  std::vector<std::pair<std::size_t, std::size_t>> big;  // (size, root)
  for (std::size_t k = 0; k < elementCount; ++k) {
    if (components.root(k) != k) continue;
    const std::size_t size = components.size(k);
    if (size >= minFragmentSize) {
      big.emplace_back(size, k);
    } else {
      ++out.debris;
      out.debrisElements += size;
    }
  }
  std::sort(big.begin(), big.end(), [](const auto& l, const auto& r) {
    return l.first != r.first ? l.first > r.first : l.second < r.second;
  });
  std::vector<std::int32_t> indexOfRoot(elementCount, -1);
  for (std::size_t f = 0; f < big.size(); ++f) {
    out.fragmentSizes.push_back(static_cast<std::int64_t>(big[f].first));
    indexOfRoot[big[f].second] = static_cast<std::int32_t>(f);
  }
  for (std::size_t k = 0; k < elementCount; ++k) out.elementFragment[k] = indexOfRoot[components.root(k)];
  return out;
}

std::size_t countFragments(const BondStore& bonds, std::size_t elementCount, std::size_t minSize) {
  BondComponents components(bonds, elementCount);
  std::size_t fragments = 0;
  for (std::size_t k = 0; k < elementCount; ++k)
    if (components.root(k) == k && components.size(k) >= minSize) ++fragments;
  return fragments;
}

std::size_t cracksCrossing(const ParticleStore& p, int dimension, const std::vector<std::int32_t>& piece,
                           double spacing, double margin) {
  const std::size_t n = p.size();
  if (n == 0 || !(spacing > 0)) return 0;
  const bool is3d = dimension == 3;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double lo[2] = {kInf, kInf}, hi[2] = {-kInf, -kInf};
  for (std::size_t k = 0; k < n; ++k) {
    const double c[2] = {p.y[k], is3d ? p.z[k] : 0.0};
    for (int a = 0; a < 2; ++a) {
      lo[a] = std::min(lo[a], c[a] - p.radius[k]);
      hi[a] = std::max(hi[a], c[a] + p.radius[k]);
    }
  }
  // Line (u, v) sits at (lo + margin + u·spacing, lo + margin + v·spacing); one row in 2D.
  auto lineCount = [&](int a) {
    const double span = hi[a] - lo[a] - 2 * margin;
    return span < 0 ? std::size_t{0} : static_cast<std::size_t>(std::floor(span / spacing)) + 1;
  };
  const std::size_t nu = lineCount(0), nv = is3d ? lineCount(1) : 1;
  if (nu == 0 || nv == 0) return 0;
  std::vector<std::vector<std::int32_t>> lines(nu * nv);  // the fragments each line meets
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t f = piece[k];
    if (f < 0) continue;
    const double r = p.radius[k], cy = p.y[k] - lo[0] - margin, cz = is3d ? p.z[k] - lo[1] - margin : 0.0;
    const auto first = [&](double c) { return static_cast<long>(std::ceil((c - r) / spacing)); };
    const auto last = [&](double c) { return static_cast<long>(std::floor((c + r) / spacing)); };
    const long u0 = std::max(0L, first(cy)), u1 = std::min(static_cast<long>(nu) - 1, last(cy));
    const long v0 = is3d ? std::max(0L, first(cz)) : 0, v1 = is3d ? std::min(static_cast<long>(nv) - 1, last(cz)) : 0;
    for (long u = u0; u <= u1; ++u)
      for (long v = v0; v <= v1; ++v) {
        const double dy = cy - u * spacing, dz = is3d ? cz - v * spacing : 0.0;
        if (dy * dy + dz * dz < r * r) lines[u * nv + v].push_back(f);
      }
  }
  std::vector<std::size_t> counts;
  for (auto& line : lines) {
    if (line.empty()) continue;
    std::sort(line.begin(), line.end());
    counts.push_back(static_cast<std::size_t>(std::unique(line.begin(), line.end()) - line.begin()) - 1);
  }
  if (counts.empty()) return 0;
  std::nth_element(counts.begin(), counts.begin() + (counts.size() - 1) / 2, counts.end());
  return counts[(counts.size() - 1) / 2];
}

}  // namespace rupture
