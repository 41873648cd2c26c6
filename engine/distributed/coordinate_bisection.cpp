#include "distributed/coordinate_bisection.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace rupture {

namespace {

void bisect(const ParticleStore& p, const std::vector<double>& work, std::vector<std::int32_t>& members,
            std::size_t first, std::size_t last, int firstRank, int parts, std::vector<int>& owner) {
  if (parts == 1 || last - first <= 1) {
    for (std::size_t k = first; k < last; ++k) owner[members[k]] = firstRank;
    return;
  }
  const std::array<const std::vector<double>*, 3> coordinate{&p.x, &p.y, &p.z};
  int axis = 0;
  double widest = -1;
  for (int a = 0; a < (p.dimension == 2 ? 2 : 3); ++a) {
    double lo = (*coordinate[a])[members[first]], hi = lo;
    for (std::size_t k = first; k < last; ++k) {
      lo = std::min(lo, (*coordinate[a])[members[k]]);
      hi = std::max(hi, (*coordinate[a])[members[k]]);
    }
    if (hi - lo > widest) { widest = hi - lo; axis = a; }
  }
  const std::vector<double>& c = *coordinate[axis];
  std::sort(members.begin() + static_cast<std::ptrdiff_t>(first), members.begin() + static_cast<std::ptrdiff_t>(last),
            [&](std::int32_t a, std::int32_t b) { return c[a] < c[b] || (c[a] == c[b] && a < b); });
  const int leftParts = parts / 2;
  double total = 0;
  for (std::size_t k = first; k < last; ++k) total += work[members[k]];
  const double target = total * leftParts / parts;
  std::size_t split = first;
  double before = 0;
  while (split < last - 1 && before + 0.5 * work[members[split]] < target) before += work[members[split++]];
  // Every rank of each side gets at least one particle.
  split = std::clamp(split, first + static_cast<std::size_t>(leftParts), last - static_cast<std::size_t>(parts - leftParts));
  bisect(p, work, members, first, split, firstRank, leftParts, owner);
  bisect(p, work, members, split, last, firstRank + leftParts, parts - leftParts, owner);
}

}  // namespace

std::vector<int> bisectCoordinates(const ParticleStore& particles, const BondStore& bonds, int parts) {
  const std::size_t n = particles.size();
  if (parts < 1) throw std::invalid_argument("bisectCoordinates: parts must be at least 1, got " + std::to_string(parts));
  if (static_cast<std::size_t>(parts) > std::max<std::size_t>(n, 1))
    throw std::invalid_argument("bisectCoordinates: " + std::to_string(parts) + " sub-domains for " +
                                std::to_string(n) + " particles (at most one sub-domain per particle)");
  std::vector<double> work(n, 1.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    work[bonds.i[b]] += 1.0;
    work[bonds.j[b]] += 1.0;
  }
  std::vector<std::int32_t> members(n);
  for (std::size_t k = 0; k < n; ++k) members[k] = static_cast<std::int32_t>(k);
  std::vector<int> owner(n, 0);
  bisect(particles, work, members, 0, n, 0, parts, owner);
  return owner;
}

}  // namespace rupture
