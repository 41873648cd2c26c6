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
// the gather's summation order. The simd pass does each slot's arithmetic with the same operations
// as the scalar law (GCC contracts the same products into FMAs in both; the identity test in
// tests/engine/test_central_bond_loop.cpp would catch a difference). No atomics: a thread writes only its own particles, and only the
// side with k = i records a broken bond (bonds.intact, the per-thread broken list).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/bond_law.hpp"
#include "core/bond_store.hpp"
#include "core/central_bond_list.hpp"
#include "core/parallel.hpp"
#include "core/particle_store.hpp"

namespace rupture {

namespace detail {

/// The first pass of a chunk: for each of its `m` slots, the partner's offset from (xk, yk, zk),
/// radius and (with kMinStretch) previous s_min, copied into the chunk buffers. Scalar on purpose:
/// vectorised, GCC makes these reads 512-bit gathers, which on Zen 5 cost more than the scalar
/// loads (the arithmetic pass after it is the one that gains from vectors).
template <bool kMinStretch, bool kRadii>
[[gnu::noinline, gnu::optimize("no-tree-vectorize")]] void readPartners(
    const std::int32_t* partner, int m, int padded, const double* packed, const double* rad, double xk, double yk,
    double zk, double* dx, double* dy, double* dz, double* rj, double* sj) {
  for (int t = 0; t < m; ++t) {
    const double* q = packed + 4 * static_cast<std::ptrdiff_t>(partner[t]);  // one cache line
    dx[t] = q[0] - xk; dy[t] = q[1] - yk; dz[t] = q[2] - zk;
    if constexpr (kMinStretch) sj[t] = q[3];
    if constexpr (kRadii) rj[t] = rad[partner[t]];
  }
  // Lanes past the last slot, up to the vector width: a finite, harmless bond (masked out later).
  for (int t = m; t < padded; ++t) {
    dx[t] = 1.0; dy[t] = 0.0; dz[t] = 0.0;
    rj[t] = 0.0;
    sj[t] = 0.0;
  }
}

/// Whether a law reads the element radii (BondGeometry::radiusI/J): unless it says it does not.
template <class Law>
constexpr bool readsRadii() {
  if constexpr (requires { Law::kReadsRadii; })
    return Law::kReadsRadii;
  else
    return true;
}

/// One slot's law and criterion, returning scalars: called inside `omp simd`, where a BondResponse
/// declared in the loop body would become a per-lane array that GCC does not vectorise.
template <class Law, class Criterion>
[[gnu::always_inline]] inline void evaluateSlot(const Law& law, const Criterion& crit, double dx, double dy, double dz,
                                                double restLength, double radiusI, double radiusJ, double stiffness,
                                                double& fjx, double& fjy, double& fjz, double& measure,
                                                double& effective) {
  BondGeometry g{};
  g.dx = dx; g.dy = dy; g.dz = dz;
  g.restLength = restLength;
  g.radiusI = radiusI; g.radiusJ = radiusJ;
  g.stiffness = stiffness;
  const BondResponse r = law.response(g);
  fjx = r.fjx; fjy = r.fjy; fjz = r.fjz;
  measure = crit.measure(r);
  effective = measure;
}

}  // namespace detail

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
  constexpr int kChunk = 128, kLanes = 8;  // kChunk a multiple of kLanes, the widest vector
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
  constexpr bool kRadii = detail::readsRadii<Law>();
  // 32-byte records from a 64-byte boundary: a record never straddles two cache lines.
  list.packed.resize(4 * p.size() + 8);
  double* packed = list.packed.data();
  packed += (64 - reinterpret_cast<std::uintptr_t>(packed) % 64) % 64 / sizeof(double);
  std::vector<std::vector<std::size_t>> found;

#pragma omp parallel if (worthParallel(bonds.size()))
  {
#pragma omp single
    found.resize(omp_get_num_threads());
    std::vector<std::size_t>& mine = found[omp_get_thread_num()];
    alignas(64) double dxb[kChunk], dyb[kChunk], dzb[kChunk], rjb[kChunk], sjb[kChunk];
    alignas(64) double fxb[kChunk], fyb[kChunk], fzb[kChunk];
    alignas(64) std::int64_t keepb[kChunk];  // 64-bit like the doubles: one vector width in the loop
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      double* q = packed + 4 * k;
      q[0] = x[k]; q[1] = y[k]; q[2] = z[k];
      q[3] = kMinStretch ? minPrevious[k] : 0.0;
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < n; ++k) {
      const double xk = x[k], yk = y[k], zk = z[k], rk = rad[k];
      double sk = 0.0;
      if constexpr (kMinStretch) sk = minPrevious[k];
      double fx = 0, fy = 0, fz = 0, lowest = 1e300;
      const std::int32_t first = start[k], last = start[k + 1];
      // The slots in chunks of kChunk, three passes each (see the file comment): scalar reads of
      // the partners, the bond arithmetic vectorised over the chunk, the sums in slot order.
      for (std::int32_t c = first; c < last; c += kChunk) {
        const int m = std::min<std::int32_t>(kChunk, last - c);
        const int padded = (m + kLanes - 1) / kLanes * kLanes;
        // The slot streams a chunk ahead: the hardware prefetcher alone leaves the loop waiting on them.
        for (int t = 0; t < m; t += 8) {
          __builtin_prefetch(L0 + c + kChunk + t);
          __builtin_prefetch(kb + c + kChunk + t);
          __builtin_prefetch(limit + c + kChunk + t);
          if (t % 16 == 0) __builtin_prefetch(partner + c + kChunk + t);
        }
        detail::readPartners<kMinStretch, kRadii>(partner + c, m, padded, packed, rad, xk, yk, zk, dxb, dyb, dzb, rjb,
                                                  sjb);
        // Whether a bond of the chunk breaks now, as an OR: a `+` reduction of the same flag lost
        // counts here (GCC 12, 512-bit vectors) and left breaking bonds unmarked.
        std::int64_t chunkBreaks = 0;
#pragma omp simd reduction(| : chunkBreaks) reduction(min : lowest)
        for (int t = 0; t < padded; ++t) {
          // A whole number of vectors, no scalar remainder: the lanes past m read no slot data and
          // keep nothing.
          const bool inside = t < m;
          double fjx, fjy, fjz, measure, effective;
          detail::evaluateSlot(lawCopy, crit, dxb[t], dyb[t], dzb[t], inside ? L0[c + t] : 1.0, kRadii ? rk : 0.0,
                               kRadii ? rjb[t] : 0.0,
                               inside ? kb[c + t] : 0.0, fjx, fjy, fjz, measure, effective);
          if constexpr (kMinStretch) effective += crit.alpha * std::max(sk, sjb[t]);
          const double threshold = inside ? limit[c + t] : kBroken;
          const bool keep = effective < threshold;
          chunkBreaks |= static_cast<std::int64_t>(!keep) & static_cast<std::int64_t>(threshold != kBroken);
          keepb[t] = keep ? 1 : 0;
          // Force on k = −(force on the partner), as the generic gather adds it.
          fxb[t] = keep ? fjx : 0.0; fyb[t] = keep ? fjy : 0.0; fzb[t] = keep ? fjz : 0.0;
          lowest = keep ? std::min(lowest, measure) : lowest;
        }
        for (int t = 0; t < m; ++t) {
          fx -= fxb[t]; fy -= fyb[t]; fz -= fzb[t];
        }
        if (chunkBreaks > 0) {
          for (int t = 0; t < m; ++t) {
            const std::int32_t s = c + t;
            if (keepb[t] || limit[s] == kBroken) continue;
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
      fxOut[k] = fx; fyOut[k] = fy; fzOut[k] = fz;
      if constexpr (kMinStretch) minNext[k] = lowest < 1e300 ? lowest : sk;
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
