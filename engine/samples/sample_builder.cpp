#include "samples/sample_builder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/cell_list.hpp"
#include "samples/material_assignment.hpp"
#include "samples/notches.hpp"
#include "samples/pores.hpp"
#include "samples/spatial_order.hpp"
#include "samples/lattice_builder.hpp"

namespace rupture {

namespace {

constexpr double kTargetFraction2D = 0.84;  // just below random close packing of polydisperse disks
constexpr double kTargetFraction3D = 0.58;
constexpr double kOverlapTolerance = 1e-2;  // × mean radius; the bonds take their rest state after it
constexpr int kMaxRelaxationSweeps = 1500;  // residual overlaps are harmless: bonds take their rest state after

double elementVolume(int dimension, double r) {
  return dimension == 2 ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

/// Jacobi relaxation of overlaps between elements and with the box walls; returns the largest
/// remaining overlap divided by the mean radius.
double relaxOverlaps(ParticleStore& p, const std::array<double, 3>& box, double meanRadius,
                     const Cancellation& cancel) {
  const std::size_t n = p.size();
  const double maxRadius = *std::max_element(p.radius.begin(), p.radius.end());
  std::vector<double> dx(n), dy(n), dz(n);
  CellList cells;
  double worst = 0;
  for (int sweep = 0; sweep < kMaxRelaxationSweeps; ++sweep) {
    cancel.throwIfRequested();
    cells.build(p, 2.0 * maxRadius);
    worst = 0;
#pragma omp parallel for schedule(static) reduction(max : worst)
    for (std::size_t a = 0; a < n; ++a) {
      // A sweep over millions of elements takes seconds: once cancelled, skip the rest of it.
      if (cancel.requested()) continue;
      double mx = 0, my = 0, mz = 0;
      const double ra = p.radius[a];
      cells.forEachNear(p.x[a], p.y[a], p.z[a], [&](std::int32_t k) {
        if (static_cast<std::size_t>(k) == a) return;
        const double ex = p.x[a] - p.x[k], ey = p.y[a] - p.y[k], ez = p.z[a] - p.z[k];
        const double d = std::sqrt(ex * ex + ey * ey + ez * ez);
        const double overlap = ra + p.radius[k] - d;
        if (overlap <= 0) return;
        worst = std::max(worst, overlap);
        // Each element moves away by 35 % of the overlap: under-relaxed Jacobi, which converges
        // near jamming where a full half-overlap push oscillates.
        const double push = 0.35 * overlap / std::max(d, 1e-12 * ra);
        mx += push * ex; my += push * ey; mz += push * ez;
      });
      // Walls: the element must lie inside the box.
      auto wall = [&](double c, double length, double& m) {
        if (c + m < ra) { worst = std::max(worst, ra - c); m = ra - c; }
        if (c + m > length - ra) { worst = std::max(worst, c - (length - ra)); m = length - ra - c; }
      };
      wall(p.x[a], box[0], mx);
      wall(p.y[a], box[1], my);
      if (p.dimension == 3) wall(p.z[a], box[2], mz);
      dx[a] = mx; dy[a] = my; dz[a] = mz;
    }
    cancel.throwIfRequested();
    if (worst < kOverlapTolerance * meanRadius) break;
    for (std::size_t a = 0; a < n; ++a) {
      p.x[a] += dx[a]; p.y[a] += dy[a]; p.z[a] += dz[a];
    }
  }
  return worst / meanRadius;
}

// How many elements a serial stage handles between two looks at the cancel flag (well under 0.2 s).
constexpr std::size_t kCancelPollInterval = 1 << 14;

void bondNeighbours(BondedSystem& system, double gap, const Cancellation& cancel) {
  ParticleStore& p = system.particles;
  const double maxRadius = *std::max_element(p.radius.begin(), p.radius.end());
  const double factor = 1.0 + 0.5 * gap;
  CellList cells;
  cells.build(p, 2.0 * maxRadius * factor);
  for (std::size_t a = 0; a < p.size(); ++a) {
    if (a % kCancelPollInterval == 0) cancel.throwIfRequested();
    cells.forEachNear(p.x[a], p.y[a], p.z[a], [&](std::int32_t k) {
      if (static_cast<std::size_t>(k) <= a) return;
      const double ex = p.x[k] - p.x[a], ey = p.y[k] - p.y[a], ez = p.z[k] - p.z[a];
      const double reach = (p.radius[a] + p.radius[k]) * factor;
      if (ex * ex + ey * ey + ez * ez < reach * reach) system.bonds.add(p, a, k);
    });
  }
}

}  // namespace

void dropUnbondedElements(BondedSystem& system) {
  std::vector<std::uint8_t> bonded(system.particles.size(), 0);
  for (std::size_t b = 0; b < system.bonds.size(); ++b)
    bonded[system.bonds.i[b]] = bonded[system.bonds.j[b]] = 1;
  if (std::find(bonded.begin(), bonded.end(), 0) != bonded.end())
    system.bonds.remap(system.particles.compact(bonded));
}

SampleReport buildSample(const SampleSpec& s, const MaterialSpec& m, BondedSystem& system,
                         const Cancellation& cancel) {
  if (s.lattice != "random") return buildLatticeSample(s, m, system, cancel);  // samples/lattice_builder.hpp
  SampleReport report = packRandomSample(s, m, system, cancel);
  finishRandomSample(s, m, system, report, cancel);
  return report;
}

SampleReport packRandomSample(const SampleSpec& s, const MaterialSpec& m, BondedSystem& system,
                              const Cancellation& cancel) {
  system = BondedSystem{};
  ParticleStore& p = system.particles;
  p.dimension = s.dimension;
  std::mt19937_64 rng(s.seed);
  SampleReport report;

  double boxVolume = s.size[0] * s.size[1] * (s.dimension == 3 ? s.size[2] : 1.0);
  const double target = s.dimension == 2 ? kTargetFraction2D : kTargetFraction3D;
  std::uniform_real_distribution<double> radiusDraw(s.elementRadius * (1.0 - s.radiusDispersion),
                                                    s.elementRadius * (1.0 + s.radiusDispersion));
  double solid = 0;
  while (solid < target * boxVolume) {
    if (p.size() % kCancelPollInterval == 0) cancel.throwIfRequested();
    const double r = radiusDraw(rng);
    double c[3] = {0, 0, 0};
    for (int a = 0; a < s.dimension; ++a)
      c[a] = std::uniform_real_distribution<double>(std::min(r, 0.5 * s.size[a]),
                                                    std::max(s.size[a] - r, 0.5 * s.size[a]))(rng);
    p.add(c[0], c[1], c[2], r);
    solid += elementVolume(s.dimension, r);
  }
  double meanRadius = 0;
  for (double r : p.radius) meanRadius += r;
  meanRadius /= static_cast<double>(p.size());
  report.relaxationOverlap = relaxOverlaps(p, s.size, meanRadius, cancel);

  bondNeighbours(system, s.bondGap, cancel);

  // Rattlers (elements of the dense packing with no bond) would float free: drop them first, so
  // that the dense sample is exactly what gets the bulk density.
  dropUnbondedElements(system);
  solid = 0;
  for (double r : p.radius) solid += elementVolume(s.dimension, r);
  report.packingFraction = solid / boxVolume;

  // Masses from the dense packing: the dense sample has the bulk density.
  report.thickness = s.dimension == 2 ? s.elementRadius : 0.0;
  // ρ / packing fraction, the expression the sample cache restores from (bit for bit the same masses).
  report.elementDensity = m.density / report.packingFraction;
  p.setMassFromDensity(report.elementDensity, report.thickness);

  // Pores (samples/pores.hpp): placed at random without overlap, then carved out of the elements.
  report.pores = placePores(s, s.porosity * boxVolume, rng, cancel);
  std::vector<std::uint8_t> keep(p.size(), 1);
  report.porosity = carvePores(s, report.pores, p, keep, cancel);
  // Drop the pore elements, then any element the pores left with no bond.
  system.bonds.remap(p.compact(keep));
  dropUnbondedElements(system);
  // Neighbours in space get neighbouring indices: the bond loop and its gather then read memory in
  // order instead of at random (samples/spatial_order.hpp).
  orderSpatially(system, 8.0 * s.elementRadius);
  return report;
}

void finishRandomSample(const SampleSpec& s, const MaterialSpec& m, BondedSystem& system, SampleReport& report,
                        const Cancellation& cancel) {
  ParticleStore& p = system.particles;
  cutNotches(s.notches, p, system.bonds);  // pre-cracks (samples/notches.hpp)
  assignMaterial(system, s, m, cancel);    // law, criterion, per-bond constants (samples/material_assignment.hpp)
  system.beam = m.beam;
  system.contact.setParameters(m.contact);
  cancel.throwIfRequested();
  system.initialize();
  report.elements = p.size();
  report.bonds = system.bonds.size();
  report.meanCoordination = p.size() ? 2.0 * static_cast<double>(report.bonds) / static_cast<double>(p.size()) : 0.0;
}

}  // namespace rupture
