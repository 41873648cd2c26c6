#include "samples/lattice_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/cell_list.hpp"
#include "bonded/materials/registry.hpp"
#include "samples/material_assignment.hpp"
#include "samples/notches.hpp"
#include "samples/pores.hpp"
#include "lattice/lattice_geometry.hpp"

namespace rupture {

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
  const MaterialStyle& style = materialStyle(m.model);
  const double reach = style.bondReach(s, m);
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
  style.pruneLatticeBonds(s, m, system.bonds);  // e.g. PMB pairs whose cell misses the horizon
  cutNotches(s.notches, p, system.bonds);
  report.packingFraction = 1.0;

  std::mt19937_64 rng(s.seed);
  const double boxVolume = s.size[0] * s.size[1] * (s.dimension == 3 ? s.size[2] : 1.0);
  if (s.porosity > 0) {  // the random packings' pores (samples/pores.hpp), carved out of the sites
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
