#include "scenarios/dynamic_tension/virial_stress.hpp"

#include <numbers>

namespace rupture {

std::vector<double> virialStress(const BondedSystem& system, double packingFraction, double thickness2d) {
  const ParticleStore& p = system.particles;
  const BondStore& bonds = system.bondLoads();
  const std::size_t n = p.size();
  std::vector<double> sigma(9 * n, 0.0);
  // Accumulate Σ_b −½(d ⊗ F_j + F_j ⊗ d) on both ends of each intact bond.
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.intact[b] <= 0.0) continue;
    const std::size_t i = static_cast<std::size_t>(bonds.i[b]), j = static_cast<std::size_t>(bonds.j[b]);
    const double d[3] = {p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]};
    const double f[3] = {bonds.fjx[b], bonds.fjy[b], bonds.fjz[b]};
    double t[9];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t[3 * r + c] = -0.5 * (d[r] * f[c] + f[r] * d[c]);
    for (int e = 0; e < 9; ++e) {
      sigma[9 * i + e] += t[e];
      sigma[9 * j + e] += t[e];
    }
  }
  constexpr double pi = std::numbers::pi;
  for (std::size_t k = 0; k < n; ++k) {
    const double r = p.radius[k];
    const double volume = p.dimension == 2 ? pi * r * r * thickness2d : 4.0 / 3.0 * pi * r * r * r;
    const double omega = volume / packingFraction;
    const double scale = 1.0 / (2.0 * omega);
    for (int e = 0; e < 9; ++e) sigma[9 * k + e] *= scale;
  }
  return sigma;
}

}  // namespace rupture
