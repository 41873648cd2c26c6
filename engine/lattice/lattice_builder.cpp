#include "lattice/lattice_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/cell_list.hpp"
#include "dem/bond_model.hpp"
#include "dem/notches.hpp"
#include "lattice/lattice_geometry.hpp"
#include "peridynamics/pmb.hpp"

namespace rupture {

namespace {

double poreMeasure(int dimension, double r) {
  return dimension == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

/// Pores of radii uniform in [min, max], placed at random without overlap until their volume reaches
/// the target (the same draw as the random packings' pores).
std::vector<Pore> drawPores(const SampleSpec& s, double target, std::mt19937_64& rng, const std::atomic<bool>* cancel) {
  std::vector<Pore> pores;
  std::uniform_real_distribution<double> radiusDraw(s.poreRadius[0], s.poreRadius[1]);
  double volume = 0;
  while (volume < target) {
    if (cancel && cancel->load(std::memory_order_relaxed)) break;
    const double r = radiusDraw(rng);
    bool placed = false;
    for (int attempt = 0; attempt < 20000 && !placed; ++attempt) {
      Pore pore{{0, 0, 0}, r};
      for (int a = 0; a < s.dimension; ++a) pore.centre[a] = std::uniform_real_distribution<double>(r, s.size[a] - r)(rng);
      placed = std::none_of(pores.begin(), pores.end(), [&](const Pore& q) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) d2 += (pore.centre[a] - q.centre[a]) * (pore.centre[a] - q.centre[a]);
        return d2 < (r + q.radius) * (r + q.radius);
      });
      if (placed) pores.push_back(pore);
    }
    if (!placed)
      throw std::runtime_error("sample.porosity: could not place the pores without overlap (" +
                               std::to_string(pores.size()) + " placed); lower the porosity or the pore radii");
    volume += poreMeasure(s.dimension, r);
  }
  return pores;
}

/// Removes the sites swallowed by the pores, scaled by a common factor so that the removed site
/// volume is closest to the porosity; returns the porosity reached.
double carvePores(const SampleSpec& s, std::vector<Pore>& pores, BondedSystem& system) {
  ParticleStore& p = system.particles;
  if (pores.empty()) return 0.0;
  std::vector<double> swallow(p.size(), 1e300);
  for (std::size_t k = 0; k < p.size(); ++k)
    for (const Pore& pore : pores) {
      const double ex = p.x[k] - pore.centre[0], ey = p.y[k] - pore.centre[1], ez = p.z[k] - pore.centre[2];
      swallow[k] = std::min(swallow[k], std::sqrt(ex * ex + ey * ey + ez * ez) / pore.radius);
    }
  std::vector<std::size_t> order(p.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return swallow[a] < swallow[b] || (swallow[a] == swallow[b] && a < b);
  });
  const double wanted = s.porosity * static_cast<double>(p.size());
  std::vector<std::uint8_t> keep(p.size(), 1);
  double removed = 0, scale = 0;
  const double maxScale = 1.5;
  for (std::size_t k : order) {
    if (swallow[k] >= maxScale) break;
    if (removed + 1 > wanted && (removed + 1 - wanted) > (wanted - removed)) break;
    removed += 1;
    keep[k] = 0;
    scale = swallow[k];
  }
  for (Pore& pore : pores) pore.radius *= scale;
  const double porosity = removed / static_cast<double>(p.size());
  system.bonds.remap(p.compact(keep));
  return porosity;
}

void dropUnbondedSites(BondedSystem& system) {
  std::vector<std::uint8_t> bonded(system.particles.size(), 0);
  for (std::size_t b = 0; b < system.bonds.size(); ++b) bonded[system.bonds.i[b]] = bonded[system.bonds.j[b]] = 1;
  if (std::find(bonded.begin(), bonded.end(), 0) != bonded.end()) system.bonds.remap(system.particles.compact(bonded));
}

/// The longest bond the material puts between sites (m).
double bondReach(const SampleSpec& s, const MaterialSpec& m, LatticeKind kind) {
  const double l = s.spacing;
  if (m.model == "pmb") return pmbBondReach(m.pmb, s.dimension, l, m.pmb.horizonFactor * l);
  if (m.model == "beam") return l * (1.0 + 1e-6);  // touching elements
  double longest = 0;
  for (const auto& o : springOffsets(kind)) longest = std::max(longest, std::sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
  return longest * l * (1.0 + 1e-6);
}

}  // namespace

SampleReport buildLatticeSample(const SampleSpec& s, const MaterialSpec& m, BondedSystem& system,
                                const std::atomic<bool>* cancel) {
  system = BondedSystem{};
  ParticleStore& p = system.particles;
  p.dimension = s.dimension;
  const LatticeKind kind = latticeKind(s.lattice);
  const double l = s.spacing;
  SampleReport report;
  report.thickness = s.dimension == 2 ? s.thickness : 0.0;

  for (const auto& site : latticeSites(kind, l, s.size)) p.add(site[0], site[1], site[2], 0.5 * l);
  if (p.size() < 2) throw std::runtime_error("sample.spacing: the box holds fewer than 2 lattice sites");
  const double siteVolume = siteMeasure(kind) * std::pow(l, s.dimension) * (s.dimension == 2 ? s.thickness : 1.0);
  report.elementDensity = m.density;
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.volume[k] = siteVolume;
    p.mass[k] = m.density * siteVolume;
    p.inertia[k] = (s.dimension == 2 ? 0.5 : 0.4) * p.mass[k] * 0.25 * l * l;
  }

  // Bonds: every pair closer than the reach, ordered by the first site (a contiguous bond list).
  const double reach = bondReach(s, m, kind);
  CellList cells;
  cells.build(p, reach);
  std::vector<std::int32_t> near;
  for (std::size_t a = 0; a < p.size(); ++a) {
    if ((a & 4095) == 0 && cancel && cancel->load(std::memory_order_relaxed)) break;
    near.clear();
    cells.forEachNear(p.x[a], p.y[a], p.z[a], [&](std::int32_t k) {
      if (static_cast<std::size_t>(k) <= a) return;
      const double ex = p.x[k] - p.x[a], ey = p.y[k] - p.y[a], ez = p.z[k] - p.z[a];
      if (ex * ex + ey * ey + ez * ez <= reach * reach) near.push_back(k);
    });
    std::sort(near.begin(), near.end());
    for (std::int32_t k : near) system.bonds.add(p, a, static_cast<std::size_t>(k));
  }
  if (m.model == "pmb") {  // "exact" partial volumes keep a pair only if its cell meets the horizon
    std::vector<std::uint8_t> keep(system.bonds.size(), 1);
    const double delta = m.pmb.horizonFactor * l;
    for (std::size_t b = 0; b < system.bonds.size(); ++b) {
      const double L0 = system.bonds.restLength[b];
      if (L0 <= delta - 0.5 * l * std::sqrt(static_cast<double>(s.dimension))) continue;
      keep[b] = pmbPartialVolume(m.pmb, system.bonds.n0x[b] * L0, system.bonds.n0y[b] * L0, system.bonds.n0z[b] * L0,
                                 s.dimension, l, delta) > 0;
    }
    system.bonds.filter(keep);
  }
  cutNotches(s.notches, p, system.bonds);
  report.packingFraction = 1.0;

  std::mt19937_64 rng(s.seed);
  const double boxVolume = s.size[0] * s.size[1] * (s.dimension == 3 ? s.size[2] : 1.0);
  if (s.porosity > 0) {
    report.pores = drawPores(s, s.porosity * boxVolume, rng, cancel);
    report.porosity = carvePores(s, report.pores, system);
  }
  dropUnbondedSites(system);

  assignMaterial(system, s, m);
  system.initialize();
  report.elements = p.size();
  report.bonds = system.bonds.size();
  report.meanCoordination = p.size() ? 2.0 * static_cast<double>(report.bonds) / static_cast<double>(p.size()) : 0.0;
  return report;
}

}  // namespace rupture
