#include "samples/spatial_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <vector>

namespace rupture {

void orderSpatially(BondedSystem& system, double stripWidth) {
  const ParticleStore& p = system.particles;
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto key = [&](std::size_t k) {
    const auto strip = static_cast<std::int64_t>(std::floor(p.y[k] / stripWidth));
    return std::tuple(strip, (strip & 1) ? -p.x[k] : p.x[k], k);  // serpentine: neighbouring strips meet
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  system.bonds.renumber(system.particles.permute(order));
}

}  // namespace rupture
