#pragma once
// The bonded loop, written once for every bond law (core/bond_law.hpp) and failure criterion
// (engine/damage/): evaluate every bond (one vectorised pass over the bond arrays, per-bond loads
// stored), then gather the loads onto particles through the incidence lists (one pass over
// particles). No atomics; the result does not depend on the thread count. The law and criterion
// are template parameters: the caller dispatches once per loop (bonded/bond_model.hpp), never per bond.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/bond_law.hpp"
#include "core/bond_store.hpp"
#include "core/parallel.hpp"
#include "core/particle_store.hpp"
#include "core/local_damping.hpp"

namespace rupture {

/// The geometry of bond b in the current configuration.
template <class Law>
[[gnu::always_inline]] inline BondGeometry bondGeometry(const ParticleStore& p, const BondStore& bonds, std::size_t b) {
  const std::int32_t i = bonds.i[b], j = bonds.j[b];
  BondGeometry g{};
  g.dx = p.x[j] - p.x[i]; g.dy = p.y[j] - p.y[i]; g.dz = p.z[j] - p.z[i];
  g.restLength = bonds.restLength[b];
  g.invRestLength = 1.0 / g.restLength;
  g.n0x = bonds.n0x[b]; g.n0y = bonds.n0y[b]; g.n0z = bonds.n0z[b];
  g.radiusI = p.radius[i]; g.radiusJ = p.radius[j];
  g.stiffness = bonds.stiffness[b];
  g.qiw = p.qw[i]; g.qix = p.qx[i]; g.qiy = p.qy[i]; g.qiz = p.qz[i];
  g.qjw = p.qw[j]; g.qjx = p.qx[j]; g.qjy = p.qy[j]; g.qjz = p.qz[j];
  return g;
}

/// Evaluates every bond, breaks (irreversibly) those whose failure measure reaches their threshold,
/// and stores the loads of the intact ones. `nodalMinStretch` (per particle, read only by criteria
/// with a nodal shift) is the smallest bond stretch of each node at the previous evaluation.
/// With kDamped, each intact bond also carries Silling's local damping (core/local_damping.hpp).
/// With kFibres (anisotropic damage, BondStore::fibreFactor), a bond loses its fibres one by one
/// instead: its integrity is that left by the last fibre whose factor × threshold the measure
/// reached, and never grows back.
/// Returns the number of bonds whose integrity dropped in this call (those that broke, without fibres).
/// With kPlanar (2D systems whose motion stays in the x-y plane, BondedSystem::planarMotion), the
/// law's planarResponse is used: z, n0_z and the in-plane quaternion parts are not read, and only
/// fjx, fjy, tiz, tjz are stored (the caller keeps fjz, tix, tiy, tjx, tjy at 0).
template <class Law, class Criterion, bool kDamped = false, bool kPlanar = false, bool kFibres = false>
std::size_t evaluateBonds(const Law& law, const Criterion& criterion, const ParticleStore& p, BondStore& bonds,
                          const double* nodalMinStretch, const SillingDamping& damping = {}) {
  // Bind the arrays to local pointers: the loop body is then plain loads, arithmetic and stores.
  const std::int32_t* bi = bonds.i.data();
  const std::int32_t* bj = bonds.j.data();
  const double *L0 = bonds.restLength.data(), *n0x = bonds.n0x.data(), *n0y = bonds.n0y.data(),
               *n0z = bonds.n0z.data(), *kb = bonds.stiffness.data(), *limit = bonds.failureThreshold.data();
  double* intact = bonds.intact.data();
  double *fjx = bonds.fjx.data(), *fjy = bonds.fjy.data(), *fjz = bonds.fjz.data();
  double *tix = bonds.tix.data(), *tiy = bonds.tiy.data(), *tiz = bonds.tiz.data();
  double *tjx = bonds.tjx.data(), *tjy = bonds.tjy.data(), *tjz = bonds.tjz.data();
  double* measured = bonds.failureMeasure.data();
  const double *x = p.x.data(), *y = p.y.data(), *z = p.z.data(), *rad = p.radius.data();
  const double *qw = p.qw.data(), *qx = p.qx.data(), *qy = p.qy.data(), *qz = p.qz.data();
  const double* sMin = nodalMinStretch;
  const double *f0 = nullptr, *f1 = nullptr, *f2 = nullptr, *k0 = nullptr, *k1 = nullptr, *k2 = nullptr;
  if constexpr (kFibres) {
    f0 = bonds.fibreFactor[0].data(); f1 = bonds.fibreFactor[1].data(); f2 = bonds.fibreFactor[2].data();
    k0 = bonds.fibreIntegrity[0].data(); k1 = bonds.fibreIntegrity[1].data(); k2 = bonds.fibreIntegrity[2].data();
  }
  const Law lawCopy = law;
  const Criterion crit = criterion;
  const SillingDamping damper = damping;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bonds.size());
  // Counted in a double (exact to 2^53): AVX2 has no conversion of doubles to 64-bit integers, and
  // one kept this loop scalar on hosts without AVX-512.
  double broken = 0;

#pragma omp parallel for simd schedule(static) reduction(+ : broken) firstprivate(lawCopy, crit) if (worthParallel(bonds.size()))
  for (std::ptrdiff_t b = 0; b < n; ++b) {
    const std::int32_t i = bi[b], j = bj[b];
    BondGeometry g{};
    g.dx = x[j] - x[i]; g.dy = y[j] - y[i];
    g.restLength = L0[b];
    g.invRestLength = 1.0 / g.restLength;
    g.n0x = n0x[b]; g.n0y = n0y[b];
    g.radiusI = rad[i]; g.radiusJ = rad[j];
    g.stiffness = kb[b];
    if constexpr (!kPlanar) {
      g.dz = z[j] - z[i];
      g.n0z = n0z[b];
    }
    if constexpr (Law::kRotational) {
      g.qiw = qw[i]; g.qiz = qz[i];
      g.qjw = qw[j]; g.qjz = qz[j];
      if constexpr (!kPlanar) {
        g.qix = qx[i]; g.qiy = qy[i];
        g.qjx = qx[j]; g.qjy = qy[j];
      }
    }
    BondResponse r;
    if constexpr (kPlanar) r = lawCopy.planarResponse(g);
    else r = lawCopy.response(g);
    if constexpr (kDamped) {
      const double length = std::sqrt(g.dx * g.dx + g.dy * g.dy + g.dz * g.dz);
      const double axial = damper.axialForce(b, i, j, length, lawCopy.stiffness(g).translational, g.restLength);
      const double perLength = axial / length;  // force on j: −F_damp e, e = (x_j − x_i)/L
      r.fjx -= perLength * g.dx; r.fjy -= perLength * g.dy; r.fjz -= perLength * g.dz;
    }
    const double m = crit.measure(r);
    double effective = m;
    if constexpr (Criterion::kNodalShift) effective += crit.alpha * std::max(sMin[i], sMin[j]);
    // Arithmetic instead of && so the loop has no control flow: now = was · [measure < threshold].
    const double was = intact[b];
    double now;
    if constexpr (kFibres) {
      // Selects, fibres in the order they fail: the last one reached sets the integrity.
      const double t = limit[b];
      double left = 1.0;
      left = effective < f0[b] * t ? left : k0[b];
      left = effective < f1[b] * t ? left : k1[b];
      left = effective < f2[b] * t ? left : k2[b];
      now = std::min(was, left);
      broken += static_cast<double>(now < was);
    } else {
      now = was * static_cast<double>(effective < limit[b]);
      broken += was - now;
    }
    intact[b] = now;
    measured[b] = m;
    fjx[b] = now * r.fjx; fjy[b] = now * r.fjy;
    if constexpr (!kPlanar) fjz[b] = now * r.fjz;
    if constexpr (Law::kRotational) {
      tiz[b] = now * r.tiz; tjz[b] = now * r.tjz;
      if constexpr (!kPlanar) {
        tix[b] = now * r.tix; tiy[b] = now * r.tiy;
        tjx[b] = now * r.tjx; tjy[b] = now * r.tjy;
      }
    }
  }
  return static_cast<std::size_t>(broken);
}

/// Sets each particle's force (and, with kTorques, torque) to the sum of its bonds' loads
/// (overwrites f and t). With kMinStretch, also the smallest failure measure (the stretch, for the
/// critical-stretch criterion) of its intact bonds into minStretch; a node without intact bond
/// keeps its previous value. With kPlanar, only f_x, f_y and t_z are summed; f_z, t_x, t_y are set to 0.
template <bool kTorques, bool kMinStretch, bool kPlanar = false>
void gatherBondLoads(const BondStore& bonds, ParticleStore& p, double* minStretch) {
  const std::int32_t* start = bonds.incidenceStart.data();
  const std::int32_t* inc = bonds.incidence.data();
  const double *fjx = bonds.fjx.data(), *fjy = bonds.fjy.data(), *fjz = bonds.fjz.data();
  const double *tix = bonds.tix.data(), *tiy = bonds.tiy.data(), *tiz = bonds.tiz.data();
  const double *tjx = bonds.tjx.data(), *tjy = bonds.tjy.data(), *tjz = bonds.tjz.data();
  const double *intact = bonds.intact.data(), *measure = bonds.failureMeasure.data();
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
#pragma omp parallel for schedule(static) if (worthParallel(p.size()))
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    double fx = 0, fy = 0, fz = 0, tx = 0, ty = 0, tz = 0;
    double lowest = 1e300;
    for (std::int32_t s = start[k]; s < start[k + 1]; ++s) {
      const std::int32_t e = inc[s], b = e >> 1;
      if constexpr (kPlanar) {
        // Branch-free: the end (e & 1) is random along the list, and a branch on it mispredicts.
        // Both torques are loaded, then selected; the sign is a ±1 factor (exact).
        const double sign = 2.0 * static_cast<double>(e & 1) - 1.0;
        fx += sign * fjx[b]; fy += sign * fjy[b];
        if constexpr (kTorques) {
          const double ti = tiz[b], tj = tjz[b];
          tz += (e & 1) ? tj : ti;
        }
      } else {
        const double sign = (e & 1) ? 1.0 : -1.0;  // end j receives F_j, end i receives −F_j
        fx += sign * fjx[b]; fy += sign * fjy[b]; fz += sign * fjz[b];
        if constexpr (kTorques) {
          tx += (e & 1) ? tjx[b] : tix[b];
          ty += (e & 1) ? tjy[b] : tiy[b];
          tz += (e & 1) ? tjz[b] : tiz[b];
        }
      }
      if constexpr (kMinStretch) lowest = intact[b] > 0.0 ? std::min(lowest, measure[b]) : lowest;
    }
    p.fx[k] = fx; p.fy[k] = fy; p.fz[k] = fz;
    if constexpr (kTorques) {
      p.tx[k] = tx; p.ty[k] = ty; p.tz[k] = tz;
    }
    if constexpr (kMinStretch) minStretch[k] = lowest < 1e300 ? lowest : minStretch[k];
  }
  if constexpr (!kTorques) {
    std::fill(p.tx.begin(), p.tx.end(), 0.0);
    std::fill(p.ty.begin(), p.ty.end(), 0.0);
    std::fill(p.tz.begin(), p.tz.end(), 0.0);
  }
}

/// Stores each bond's loads on the current configuration without breaking any: the force on j of
/// the intact ones (0 for broken bonds) and every bond's failure measure, as evaluateBonds leaves
/// them. For paths that do not store per-bond loads each step (core/central_bond_loop.hpp), and for
/// a decomposed run's gathered whole system. kPlanar: the law's planarResponse, as evaluateBonds
/// takes it in planar motion, so that the numbers are the loop's own to the last bit.
template <class Law, class Criterion, bool kPlanar = false>
void storeBondLoads(const Law& law, const Criterion& criterion, const ParticleStore& p, const BondStore& bonds) {
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bonds.size());
#pragma omp parallel for schedule(static) if (worthParallel(bonds.size()))
  for (std::ptrdiff_t b = 0; b < n; ++b) {
    BondResponse r;
    if constexpr (kPlanar) r = law.planarResponse(bondGeometry<Law>(p, bonds, b));
    else r = law.response(bondGeometry<Law>(p, bonds, b));
    const double now = bonds.intact[b];
    bonds.fjx[b] = now * r.fjx; bonds.fjy[b] = now * r.fjy; bonds.fjz[b] = now * r.fjz;
    bonds.failureMeasure[b] = criterion.measure(r);
  }
}

/// Elastic energy stored in the intact bonds (J). With kPlanar (as in evaluateBonds), the law's
/// planarEnergy where it has one.
template <class Law, bool kPlanar = false>
double bondEnergy(const Law& law, const ParticleStore& p, const BondStore& bonds) {
  double e = 0;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(bonds.size());
  // A select instead of a branch, so that the loop vectorises (a broken bond's response is computed
  // and dropped; it is not multiplied by 0, which could turn an infinite one into NaN). A partly
  // damaged bond (anisotropic damage) stores its integrity times the intact bond's energy.
#pragma omp parallel for simd reduction(+ : e) schedule(static) if (worthParallel(bonds.size()))
  for (std::ptrdiff_t b = 0; b < n; ++b) {
    double energy;
    if constexpr (kPlanar) energy = law.planarEnergy(bondGeometry<Law>(p, bonds, b));
    else energy = law.response(bondGeometry<Law>(p, bonds, b)).energy;
    e += bonds.intact[b] > 0.0 ? bonds.intact[b] * energy : 0.0;
  }
  return e;
}

/// Sums each intact bond's Gershgorin stiffness onto its two particles (N/m and N·m/rad).
template <class Law>
void accumulateBondStiffness(const Law& law, const ParticleStore& p, const BondStore& bonds,
                             std::vector<double>& translational, std::vector<double>& rotational) {
  translational.assign(p.size(), 0.0);
  rotational.assign(p.size(), 0.0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.intact[b] <= 0.0) continue;  // a partly damaged bond counts whole: a safe bound
    const BondStiffness k = law.stiffness(bondGeometry<Law>(p, bonds, b));
    translational[bonds.i[b]] += k.translational; translational[bonds.j[b]] += k.translational;
    rotational[bonds.i[b]] += k.rotational; rotational[bonds.j[b]] += k.rotational;
  }
}

}  // namespace rupture
