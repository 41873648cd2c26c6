#pragma once
// The bonded loop of central-force laws (Law::kRotational false: lattice springs, PMB bonds), one
// pass over particles through their full partner list (core/central_bond_list.hpp). Each particle
// evaluates each of its bonds from its own side and sums the force on itself in registers: no
// per-bond load arrays, no gather pass, and the only random reads are particle positions (which
// stay in cache), instead of a half-list pass that stores per-bond loads and a gather that reads
// them back at random (core/bond_loop.hpp, kept for rotational laws and damped bonds).
//
// Why it agrees bit for bit with the generic loop: the side k evaluates the bond with
// dx = x_partner − x_k, the exact negation of the other side's; a central law's length, stretch,
// energy and axial force are the same numbers either way and its force the exact negation, so
// both sides take the same break decision (the nodal shift uses max(s_min,i, s_min,j), symmetric)
// and the force on k is −F_partner, as the gather gives it; slots are in ascending bond order,
// the gather's summation order. No atomics: a thread writes only its own particles, and only the
// side with k = i records a broken bond (bonds.intact, the per-thread broken list).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "core/bond_law.hpp"
#include "core/bond_store.hpp"
#include "core/central_bond_list.hpp"
#include "core/parallel.hpp"
#include "core/particle_store.hpp"

namespace rupture {

/// Evaluates every bond of a central law, breaks (irreversibly) those whose failure measure
/// reaches their threshold, and sets each particle's force to the sum over its intact bonds
/// (overwrites f; the torques are set to zero). With kMinStretch (a criterion with a nodal shift
/// and α != 0), also writes each node's smallest measure over its intact bonds to `minNext`
/// (its `minPrevious` value when it has none), reading the previous evaluation's from
/// `minPrevious`. The bonds that broke are set broken in `bonds.intact` and appended to `broken`
/// in ascending bond order. Per-bond loads (bonds.fjx, failureMeasure) are not written.
template <class Law, class Criterion, bool kMinStretch>
void evaluateCentralBonds(const Law& law, const Criterion& criterion, ParticleStore& p, BondStore& bonds,
                          CentralBondList& list, const double* minPrevious, double* minNext,
                          std::vector<std::size_t>& broken) {
  static_assert(!Law::kRotational, "the central-force loop is for laws without torques");
  constexpr double kBroken = -std::numeric_limits<double>::infinity();
  const std::int32_t* start = bonds.incidenceStart.data();
  const std::int32_t* inc = bonds.incidence.data();
  const std::int32_t* partner = list.partner.data();
  const double *L0 = list.restLength.data(), *kb = list.stiffness.data();
  double* limit = list.limit.data();
  double* intact = bonds.intact.data();
  const double *x = p.x.data(), *y = p.y.data(), *z = p.z.data(), *rad = p.radius.data();
  double *fxOut = p.fx.data(), *fyOut = p.fy.data(), *fzOut = p.fz.data();
  const Law lawCopy = law;
  const Criterion crit = criterion;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(p.size());
  std::vector<std::vector<std::size_t>> found;

#pragma omp parallel if (worthParallel(bonds.size()))
  {
#pragma omp single
    found.resize(omp_get_num_threads());
    std::vector<std::size_t>& mine = found[omp_get_thread_num()];
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      const double xk = x[k], yk = y[k], zk = z[k], rk = rad[k];
      double sk = 0.0;
      if constexpr (kMinStretch) sk = minPrevious[k];
      double fx = 0, fy = 0, fz = 0, lowest = 1e300;
      int breaks = 0;
      const std::int32_t first = start[k], last = start[k + 1];
      // Slot s of k: the response, its failure measure and whether the bond stays intact.
      auto evaluate = [&](std::int32_t s, BondResponse& r, double& m) [[gnu::always_inline]] {
        const std::int32_t j = partner[s];
        BondGeometry g{};
        g.dx = x[j] - xk; g.dy = y[j] - yk; g.dz = z[j] - zk;
        g.restLength = L0[s];
        g.radiusI = rk; g.radiusJ = rad[j];
        g.stiffness = kb[s];
        r = lawCopy.response(g);
        m = crit.measure(r);
        double effective = m;
        if constexpr (kMinStretch) effective += crit.alpha * std::max(sk, minPrevious[j]);
        return effective < limit[s];
      };
      // The pass only reads the slots; the rare particle with a bond breaking now marks its slots
      // in a second pass below. Deliberately scalar: `omp simd` vectorises it with 512-bit gathers
      // of the partner positions, which measured 15-20 % slower on W2 (Zen 5, GCC 12); scalar, the
      // sums also run in the generic gather's order, so both loops give the same bits.
      for (std::int32_t s = first; s < last; ++s) {
        BondResponse r;
        double m;
        const bool keep = evaluate(s, r, m);
        breaks += !keep && limit[s] != kBroken;
        const double now = keep ? 1.0 : 0.0;
        // Force on k = −(force on the partner), as the generic gather adds it.
        fx -= now * r.fjx; fy -= now * r.fjy; fz -= now * r.fjz;
        lowest = keep ? std::min(lowest, m) : lowest;
      }
      fxOut[k] = fx; fyOut[k] = fy; fzOut[k] = fz;
      if constexpr (kMinStretch) minNext[k] = lowest < 1e300 ? lowest : sk;
      if (breaks > 0) {
        for (std::int32_t s = first; s < last; ++s) {
          BondResponse r;
          double m;
          if (limit[s] == kBroken || evaluate(s, r, m)) continue;
          limit[s] = kBroken;
          // Only the side with k = i records the bond: once, by one thread.
          const std::int32_t e = inc[s], b = e >> 1;
          if ((e & 1) == 0) {
            intact[b] = 0.0;
            mine.push_back(static_cast<std::size_t>(b));
          }
        }
      }
    }
  }
  const std::size_t before = broken.size();
  for (const auto& part : found) broken.insert(broken.end(), part.begin(), part.end());
  std::sort(broken.begin() + static_cast<std::ptrdiff_t>(before), broken.end());
  std::fill(p.tx.begin(), p.tx.end(), 0.0);
  std::fill(p.ty.begin(), p.ty.end(), 0.0);
  std::fill(p.tz.begin(), p.tz.end(), 0.0);
}

}  // namespace rupture
