#include "lattice/lattice_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/cell_list.hpp"
#include "dem/bond_model.hpp"
#include "dem/notches.hpp"
#include "dem/pores.hpp"
#include "lattice/lattice_geometry.hpp"
#include "peridynamics/pmb.hpp"

namespace rupture {

namespace {

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
                                const Cancellation& cancel) {
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
    if ((a & 4095) == 0) cancel.throwIfRequested();
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
  if (s.porosity > 0) {  // the random packings' pores (dem/pores.hpp), carved out of the sites
    report.pores = placePores(s, s.porosity * boxVolume, rng, cancel);
    std::vector<std::uint8_t> keep(p.size(), 1);
    report.porosity = carvePores(s, report.pores, p, keep, cancel);
    system.bonds.remap(p.compact(keep));
  }
  dropUnbondedElements(system);

  assignMaterial(system, s, m, cancel);
  cancel.throwIfRequested();
  system.initialize();
  report.elements = p.size();
  report.bonds = system.bonds.size();
  report.meanCoordination = p.size() ? 2.0 * static_cast<double>(report.bonds) / static_cast<double>(p.size()) : 0.0;
  return report;
}

}  // namespace rupture
