#include "samples/inclusions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <unordered_map>

namespace rupture {

std::vector<Pore> placeInclusions(const SampleSpec& s, const Cancellation& cancel) {
  if (s.inclusions.volumeFraction <= 0) return {};
  SampleSpec asPores = s;  // the pores' placement, with the inclusions' radii
  asPores.poreRadius = s.inclusions.radius;
  asPores.porosity = s.inclusions.volumeFraction;
  double volume = 1;
  for (int a = 0; a < s.dimension; ++a) volume *= s.size[a];
  std::mt19937_64 rng(s.seed ^ 0xC2B2AE3D27D4EB4Full);  // a stream of its own (packing, pores, grains)
  try {
    return placePores(asPores, s.inclusions.volumeFraction * volume, rng, cancel);
  } catch (const RunCancelled&) {
    throw;
  } catch (const std::runtime_error&) {
    throw std::runtime_error("sample.inclusions.volume_fraction: could not place the inclusions without overlap; "
                             "lower the volume fraction or the radii");
  }
}

std::vector<std::uint8_t> insideInclusions(const std::vector<Pore>& inclusions, const ParticleStore& p) {
  std::vector<std::uint8_t> inside(p.size(), 0);
  if (inclusions.empty()) return inside;
  double largest = 0;
  for (const Pore& c : inclusions) largest = std::max(largest, c.radius);
  // Inclusions binned on cells of edge 2 r_max: a point can only lie in those of its own cell's
  // neighbours.
  const double inverseEdge = 0.5 / largest;
  const bool is3d = p.dimension == 3;
  auto cellKey = [&](double x, double y, double z, int dx, int dy, int dz) {
    const std::int64_t cx = static_cast<std::int64_t>(std::floor(x * inverseEdge)) + dx + (1 << 20);
    const std::int64_t cy = static_cast<std::int64_t>(std::floor(y * inverseEdge)) + dy + (1 << 20);
    const std::int64_t cz = (is3d ? static_cast<std::int64_t>(std::floor(z * inverseEdge)) : 0) + dz + (1 << 20);
    return (cz << 42) | (cy << 21) | cx;
  };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
  for (std::size_t k = 0; k < inclusions.size(); ++k)
    cells[cellKey(inclusions[k].centre[0], inclusions[k].centre[1], inclusions[k].centre[2], 0, 0, 0)].push_back(k);
  const int reachZ = is3d ? 1 : 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double z = is3d ? p.z[k] : 0.0;
    for (int dz = -reachZ; dz <= reachZ && !inside[k]; ++dz)
      for (int dy = -1; dy <= 1 && !inside[k]; ++dy)
        for (int dx = -1; dx <= 1 && !inside[k]; ++dx) {
          const auto it = cells.find(cellKey(p.x[k], p.y[k], z, dx, dy, dz));
          if (it == cells.end()) continue;
          for (std::size_t c : it->second) {
            const Pore& q = inclusions[c];
            const double ex = p.x[k] - q.centre[0], ey = p.y[k] - q.centre[1], ez = is3d ? z - q.centre[2] : 0.0;
            if (ex * ex + ey * ey + ez * ez <= q.radius * q.radius) { inside[k] = 1; break; }
          }
        }
  }
  return inside;
}

void applyInclusionProperties(const InclusionSpec& spec, const std::vector<std::uint8_t>& inside,
                              ParticleStore& p, BondStore& bonds) {
  for (std::size_t k = 0; k < p.size(); ++k)
    if (inside[k]) {
      p.mass[k] *= spec.densityFactor;
      p.inertia[k] *= spec.densityFactor;
    }
  const double a = spec.stiffnessFactor, series = 2 * a / (1 + a);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const int ends = inside[bonds.i[b]] + inside[bonds.j[b]];
    if (ends == 2) {
      bonds.stiffness[b] *= a;
      bonds.strength[b] *= spec.strengthFactor;
    } else if (ends == 1) {
      bonds.stiffness[b] *= series;
      bonds.strength[b] *= spec.interfaceStrengthFactor;
    }
  }
}

}  // namespace rupture
