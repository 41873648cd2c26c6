#include "samples/grains.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace rupture {

std::vector<std::array<double, 3>> grainSeeds(const SampleSpec& s) {
  // A stream of its own: the packing and the pores draw from mt19937_64(seed).
  std::mt19937_64 rng(s.seed ^ 0x9E3779B97F4A7C15ull);
  std::vector<std::array<double, 3>> seeds(static_cast<std::size_t>(s.grains.count));
  for (auto& p : seeds)
    for (int a = 0; a < 3; ++a)
      p[a] = a < s.dimension ? std::uniform_real_distribution<double>(0.0, s.size[a])(rng) : 0.0;
  return seeds;
}

std::vector<std::int32_t> voronoiGrains(const SampleSpec& s, const ParticleStore& particles, const Cancellation& cancel) {
  const std::vector<std::array<double, 3>> seeds = grainSeeds(s);
  const int d = s.dimension;
  // A grid of about one seed per cell; a particle looks at rings of cells around its own until
  // no unvisited cell can hold a nearer seed (ring r + 1 is at least r cells away).
  double volume = 1;
  for (int a = 0; a < d; ++a) volume *= s.size[a];
  const double cell = std::pow(volume / static_cast<double>(seeds.size()), 1.0 / d);
  std::array<int, 3> n{1, 1, 1};
  for (int a = 0; a < d; ++a) n[a] = std::max(1, static_cast<int>(std::ceil(s.size[a] / cell)));
  auto cellOf = [&](double c, int a) { return std::clamp(static_cast<int>(std::floor(c / cell)), 0, n[a] - 1); };
  std::vector<std::vector<std::int32_t>> members(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  for (std::size_t k = 0; k < seeds.size(); ++k)
    members[(static_cast<std::size_t>(cellOf(seeds[k][2], 2)) * n[1] + cellOf(seeds[k][1], 1)) * n[0] + cellOf(seeds[k][0], 0)]
        .push_back(static_cast<std::int32_t>(k));
  const int maxRing = *std::max_element(n.begin(), n.end());

  std::vector<std::int32_t> grain(particles.size(), 0);
  for (std::size_t k = 0; k < particles.size(); ++k) {
    if (k % 65536 == 0) cancel.throwIfRequested();
    const double p[3] = {particles.x[k], particles.y[k], d == 3 ? particles.z[k] : 0.0};
    const int c[3] = {cellOf(p[0], 0), cellOf(p[1], 1), d == 3 ? cellOf(p[2], 2) : 0};
    double best = std::numeric_limits<double>::infinity();
    std::int32_t nearest = 0;
    for (int ring = 0; ring <= maxRing; ++ring) {
      const int rz = d == 3 ? ring : 0;
      for (int iz = c[2] - rz; iz <= c[2] + rz; ++iz)
        for (int iy = c[1] - ring; iy <= c[1] + ring; ++iy)
          for (int ix = c[0] - ring; ix <= c[0] + ring; ++ix) {
            const int chebyshev = std::max({std::abs(ix - c[0]), std::abs(iy - c[1]), std::abs(iz - c[2])});
            if (chebyshev != ring || ix < 0 || iy < 0 || iz < 0 || ix >= n[0] || iy >= n[1] || iz >= n[2]) continue;
            for (std::int32_t g : members[(static_cast<std::size_t>(iz) * n[1] + iy) * n[0] + ix]) {
              double r2 = 0;
              for (int a = 0; a < 3; ++a) r2 += (p[a] - seeds[g][a]) * (p[a] - seeds[g][a]);
              if (r2 < best || (r2 == best && g < nearest)) { best = r2; nearest = g; }
            }
          }
      if (std::isfinite(best) && std::sqrt(best) <= ring * cell) break;
    }
    grain[k] = nearest;
  }
  return grain;
}

std::size_t weakenGrainBoundaries(const std::vector<std::int32_t>& grain, double factor, BondStore& bonds) {
  std::size_t boundary = 0;
  for (std::size_t b = 0; b < bonds.size(); ++b)
    if (grain[bonds.i[b]] != grain[bonds.j[b]]) {
      bonds.strength[b] *= factor;  // the strength factor: beams reset their threshold to σ_f at initialize
      ++boundary;
    }
  return boundary;
}

}  // namespace rupture
