#include "peridynamics/pmb.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

namespace rupture {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr int kQuadrature = 16;  // points per axis for the exact partial volume
}  // namespace

double pmbMicromodulus(int dimension, double E, double delta, double thickness) {
  if (dimension == 3) return 18.0 * pmbBulkModulus(E) / (kPi * std::pow(delta, 4));
  return 9.0 * E / (kPi * thickness * std::pow(delta, 3));
}

double pmbCriticalStretch(int dimension, double E, double delta, double G0) {
  if (dimension == 3) return std::sqrt(5.0 * G0 / (9.0 * pmbBulkModulus(E) * delta));
  return std::sqrt(4.0 * kPi * G0 / (9.0 * E * delta));
}

double pmbCriticalEnergyDensity(int dimension, double delta, double thickness, double G0) {
  if (dimension == 3) return 4.0 * G0 / (kPi * std::pow(delta, 4));
  return 3.0 * G0 / (2.0 * thickness * std::pow(delta, 3));
}

double pmbPartialVolume(const PmbSpec& spec, double xx, double xy, double xz, int dimension, double cell,
                        double delta) {
  const double length = std::sqrt(xx * xx + xy * xy + xz * xz);
  if (spec.partialVolume == "linear") {
    const double h = 0.5 * cell;  // LAMMPS: 1 at δ − h, ½ at δ
    if (length > delta * (1.0 + 1e-12)) return 0.0;
    if (std::fabs(length - delta) <= h) return -length / (2.0 * h) + 1.0 + (delta - h) / (2.0 * h);
    return 1.0;
  }
  // Midpoint quadrature of the cell centred on the partner.
  const int nz = dimension == 3 ? kQuadrature : 1;
  int inside = 0, total = 0;
  const double d2 = delta * delta;
  for (int a = 0; a < kQuadrature; ++a)
    for (int b = 0; b < kQuadrature; ++b)
      for (int c = 0; c < nz; ++c) {
        const double px = xx + cell * ((a + 0.5) / kQuadrature - 0.5);
        const double py = xy + cell * ((b + 0.5) / kQuadrature - 0.5);
        const double pz = dimension == 3 ? xz + cell * ((c + 0.5) / kQuadrature - 0.5) : 0.0;
        inside += px * px + py * py + pz * pz <= d2;
        ++total;
      }
  return static_cast<double>(inside) / total;
}

double pmbBondReach(const PmbSpec& spec, int dimension, double cell, double delta) {
  if (spec.partialVolume == "linear") return delta * (1.0 + 1e-9);
  return delta + 0.5 * cell * std::sqrt(static_cast<double>(dimension));
}

void assignPmbBonds(const PmbSpec& spec, int dimension, double spacing, double thickness,
                    const ParticleStore& p, BondStore& bonds) {
  const double delta = spec.horizonFactor * spacing;
  const double c = pmbMicromodulus(dimension, spec.youngModulus, delta, thickness);
  double s0 = spec.criticalStretch;
  if (std::isnan(s0) && !std::isnan(spec.fractureEnergy))
    s0 = pmbCriticalStretch(dimension, spec.youngModulus, delta, spec.fractureEnergy);
  const bool byEnergy = spec.criterion == "critical_energy";
  const double wc = byEnergy ? pmbCriticalEnergyDensity(dimension, delta, thickness, spec.fractureEnergy) : 0.0;
  // β depends only on the offset on a regular lattice: cache it by the offset in spacings.
  std::map<std::tuple<long, long, long>, double> cache;
  auto key = [&](double v) { return std::lround(v / spacing * 1e4); };
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const std::int32_t i = bonds.i[b], j = bonds.j[b];
    const double L0 = bonds.restLength[b];
    const double xx = bonds.n0x[b] * L0, xy = bonds.n0y[b] * L0, xz = bonds.n0z[b] * L0;
    const auto k = std::make_tuple(key(xx), key(xy), key(xz));
    auto it = cache.find(k);
    if (it == cache.end()) it = cache.emplace(k, pmbPartialVolume(spec, xx, xy, xz, dimension, spacing, delta)).first;
    const double beta = it->second;
    const double pairVolume = beta * p.volume[i] * p.volume[j];
    bonds.stiffness[b] = c * pairVolume / L0;
    if (byEnergy) bonds.threshold[b] = wc * pairVolume;
    else bonds.threshold[b] = std::isnan(s0) ? std::numeric_limits<double>::infinity() : s0;
  }
}

}  // namespace rupture
