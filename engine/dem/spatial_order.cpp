#include "dem/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

namespace rupture {

namespace {

template <class T>
void permute(std::vector<T>& v, const std::vector<std::size_t>& order) {
  if (v.size() != order.size()) return;  // an array not in use (e.g. volumes before masses are set)
  std::vector<T> old = std::move(v);
  v.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) v[k] = old[order[k]];
}

}  // namespace

void orderSpatially(BondedSystem& system, double stripWidth) {
  ParticleStore& p = system.particles;
  const std::size_t n = p.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t k) {
    const auto strip = static_cast<std::int64_t>(std::floor(p.y[k] / stripWidth));
    return std::tuple(strip, (strip & 1) ? -p.x[k] : p.x[k], k);  // serpentine: neighbouring strips meet
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  std::vector<std::int32_t> newIndex(n);
  for (std::size_t k = 0; k < n; ++k) newIndex[order[k]] = static_cast<std::int32_t>(k);
  for (auto* v : {&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.fx, &p.fy, &p.fz, &p.qw, &p.qx, &p.qy, &p.qz, &p.wx,
                  &p.wy, &p.wz, &p.tx, &p.ty, &p.tz, &p.radius, &p.mass, &p.inertia, &p.volume})
    permute(*v, order);
  permute(p.fixedDofs, order);

  // Bonds keep i < j: a bond whose ends swap order takes the opposite reference direction.
  BondStore& bonds = system.bonds;
  const std::size_t m = bonds.size();
  for (std::size_t b = 0; b < m; ++b) {
    std::int32_t a = newIndex[bonds.i[b]], c = newIndex[bonds.j[b]];
    if (a > c) {
      std::swap(a, c);
      bonds.n0x[b] = -bonds.n0x[b]; bonds.n0y[b] = -bonds.n0y[b]; bonds.n0z[b] = -bonds.n0z[b];
    }
    bonds.i[b] = a;
    bonds.j[b] = c;
  }
  std::vector<std::size_t> bondOrder(m);
  std::iota(bondOrder.begin(), bondOrder.end(), std::size_t{0});
  std::sort(bondOrder.begin(), bondOrder.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(bonds.i[a], bonds.j[a], a) < std::tie(bonds.i[b], bonds.j[b], b);
  });
  permute(bonds.i, bondOrder);
  permute(bonds.j, bondOrder);
  for (auto* v : {&bonds.restLength, &bonds.n0x, &bonds.n0y, &bonds.n0z, &bonds.intact, &bonds.stiffness,
                  &bonds.threshold, &bonds.strength})
    permute(*v, bondOrder);
  for (BondStore::CutPair& c : bonds.cutPairs) {
    c.i = newIndex[c.i];
    c.j = newIndex[c.j];
  }
}

}  // namespace rupture
