#include "samples/pores.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/cell_list.hpp"

namespace rupture {
namespace {

double elementVolume(int dimension, double r) {
  return dimension == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

/// Pores placed so far, binned on a grid of cells of edge 2 r_max (occupied cells only), so the
/// overlap test of a candidate looks at its 3^d neighbouring cells instead of every pore.
class PoreGrid {
public:
  PoreGrid(int dimension, double maxRadius) : m_dimension(dimension), m_inverseEdge(0.5 / maxRadius) {}

  bool overlapsAny(const Pore& pore, const std::vector<Pore>& pores) const {
    const auto c = cellOf(pore);
    const int reach[3] = {1, 1, m_dimension == 3 ? 1 : 0};
    for (std::int64_t a = -reach[2]; a <= reach[2]; ++a)
      for (std::int64_t b = -reach[1]; b <= reach[1]; ++b)
        for (std::int64_t d = -reach[0]; d <= reach[0]; ++d) {
          auto it = m_cells.find(key({c[0] + d, c[1] + b, c[2] + a}));
          if (it == m_cells.end()) continue;
          for (std::size_t index : it->second) {
            const Pore& q = pores[index];
            double d2 = 0;
            for (int ax = 0; ax < 3; ++ax) d2 += (pore.centre[ax] - q.centre[ax]) * (pore.centre[ax] - q.centre[ax]);
            if (d2 < (pore.radius + q.radius) * (pore.radius + q.radius)) return true;
          }
        }
    return false;
  }
  void insert(const Pore& pore, std::size_t index) { m_cells[key(cellOf(pore))].push_back(index); }

private:
  std::array<std::int64_t, 3> cellOf(const Pore& pore) const {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int ax = 0; ax < m_dimension; ++ax) c[ax] = static_cast<std::int64_t>(std::floor(pore.centre[ax] * m_inverseEdge));
    return c;
  }
  static std::int64_t key(const std::array<std::int64_t, 3>& c) {  // 21 bits per axis: cells < 2^20 per edge
    return ((c[2] + (1 << 20)) << 42) | ((c[1] + (1 << 20)) << 21) | (c[0] + (1 << 20));
  }
  int m_dimension;
  double m_inverseEdge;
  std::unordered_map<std::int64_t, std::vector<std::size_t>> m_cells;
};

}  // namespace

std::vector<Pore> placePores(const SampleSpec& s, double poreVolumeTarget, std::mt19937_64& rng,
                             const Cancellation& cancel) {
  constexpr int kPlacementAttempts = 20000;
  std::vector<Pore> pores;
  if (s.porosity <= 0) return pores;
  std::uniform_real_distribution<double> radiusDraw(s.poreRadius[0], s.poreRadius[1]);
  PoreGrid grid(s.dimension, s.poreRadius[1]);
  double volume = 0;
  while (volume < poreVolumeTarget) {
    cancel.throwIfRequested();
    const double r = radiusDraw(rng);
    bool placed = false;
    for (int attempt = 0; attempt < kPlacementAttempts && !placed; ++attempt) {
      Pore pore{{0, 0, 0}, r};
      for (int a = 0; a < s.dimension; ++a)
        pore.centre[a] = std::uniform_real_distribution<double>(r, s.size[a] - r)(rng);
      if (grid.overlapsAny(pore, pores)) continue;
      placed = true;
      grid.insert(pore, pores.size());
      pores.push_back(pore);
    }
    if (!placed)
      throw std::runtime_error("sample.porosity: could not place the pores without overlap (" +
                               std::to_string(pores.size()) + " placed); lower the porosity or the pore radii");
    volume += elementVolume(s.dimension, r);
  }
  return pores;
}

double carvePores(const SampleSpec& s, std::vector<Pore>& pores, const ParticleStore& p,
                  std::vector<std::uint8_t>& keep, const Cancellation& cancel) {
  if (pores.empty()) return 0.0;
  // The largest scale keeping pores apart and inside the box.
  double maxScale = 1.5;
  for (std::size_t a = 0; a < pores.size(); ++a) {
    if (a % 256 == 0) cancel.throwIfRequested();
    const Pore& pa = pores[a];
    for (int ax = 0; ax < s.dimension; ++ax)
      maxScale = std::min({maxScale, pa.centre[ax] / pa.radius, (s.size[ax] - pa.centre[ax]) / pa.radius});
    for (std::size_t b = a + 1; b < pores.size(); ++b) {
      const Pore& pb = pores[b];
      double d2 = 0;
      for (int ax = 0; ax < 3; ++ax) d2 += (pa.centre[ax] - pb.centre[ax]) * (pa.centre[ax] - pb.centre[ax]);
      maxScale = std::min(maxScale, std::sqrt(d2) / (pa.radius + pb.radius));
    }
  }
  // Only elements within maxScale × radius of a pore centre can be carved: visit those through
  // a cell list instead of testing every element against every pore.
  std::vector<double> swallowScale(p.size(), 1e300);
  CellList cells;
  cells.build(p, 2.0 * s.elementRadius);
  for (std::size_t q = 0; q < pores.size(); ++q) {
    if (q % 64 == 0) cancel.throwIfRequested();
    const Pore& pore = pores[q];
    const double reach = maxScale * pore.radius;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int ax = 0; ax < 3; ++ax) { lo[ax] = pore.centre[ax] - reach; hi[ax] = pore.centre[ax] + reach; }
    cells.forEachInBox(lo, hi, [&](std::int32_t k) {
      const double ex = p.x[k] - pore.centre[0], ey = p.y[k] - pore.centre[1], ez = p.z[k] - pore.centre[2];
      swallowScale[k] = std::min(swallowScale[k], std::sqrt(ex * ex + ey * ey + ez * ez) / pore.radius);
    });
  }
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (swallowScale[k] < maxScale) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return swallowScale[a] < swallowScale[b] || (swallowScale[a] == swallowScale[b] && a < b);
  });
  double solid = 0;
  for (std::size_t k = 0; k < p.size(); ++k) solid += elementVolume(s.dimension, p.radius[k]);
  const double wanted = s.porosity * solid;
  double removed = 0, scale = 0;
  for (std::size_t n = 0; n < order.size(); ++n) {
    const std::size_t k = order[n];
    const double v = elementVolume(s.dimension, p.radius[k]);
    // Stop where the removed volume is closest to the target.
    if (removed + v > wanted && (removed + v - wanted) > (wanted - removed)) break;
    removed += v;
    keep[k] = 0;
    scale = swallowScale[k];
  }
  // Report pores at the radius that was actually carved (just above the last swallowed centre).
  for (Pore& pore : pores) pore.radius *= scale;
  return removed / solid;
}

}  // namespace rupture
