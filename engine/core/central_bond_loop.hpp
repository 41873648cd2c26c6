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
#include <cstring>
#include <limits>
#include <vector>

#include "core/bond_law.hpp"
#include "core/bond_store.hpp"
#include "core/central_bond_list.hpp"
#include "core/parallel.hpp"
#include "core/particle_store.hpp"

namespace rupture {

namespace detail {

/// The first pass of a chunk: for each of its `m` slots, the partner's packed record (x, y, z,
/// previous s_min) and, in the compact form (kCompact), its kind's record (rest length, stiffness,
/// threshold, 1/rest length), each copied whole (32 bytes: one load, one store) into the chunk
/// buffers, plus the partner's radius when the law reads it. Scalar on purpose: vectorised, GCC makes these reads
/// 512-bit gathers, which on Zen 5 cost more than the scalar loads; and whole-record copies
/// because this pass is bound by its stores (the arithmetic pass unpacks the records in vectors).
///
/// The same pass also takes, in slot order, the sums of the previous chunk's `pm` forces (fxp, fyp,
/// fzp) into (sx, sy, sz): software pipelining. On their own those sums are three chains of
/// dependent subtractions, one latency (3 cycles on Zen 4) a slot, and the core cannot run the
/// next chunk's copies beside them (a chunk's sums are more instructions than the reorder buffer
/// holds); interleaved with the copies, which depend on nothing of theirs, each hides the other.
/// The sums are the same subtractions in the same order: the same bits. (Without
/// no-tree-loop-distribution GCC splits the fused loop back into a copy loop and a sum loop.)
template <bool kRadii, bool kCompact>
[[gnu::noinline, gnu::optimize("no-tree-vectorize", "no-tree-loop-distribution")]] void readPartners(
    const std::int32_t* partner, const std::uint16_t* kind, const CentralBondList::Kind* kinds, int m, int padded,
    const double* packed, const double* rad, double xk, double yk, double zk, double* rec, double* rj,
    double* kindRec, const double* fxp, const double* fyp, const double* fzp, int pm, double& sx, double& sy,
    double& sz) {
  double ax = sx, ay = sy, az = sz;
  const auto copy = [&](int t) {
    std::memcpy(rec + 4 * t, packed + 4 * static_cast<std::ptrdiff_t>(partner[t]), 4 * sizeof(double));
    if constexpr (kRadii) rj[t] = rad[partner[t]];
    if constexpr (kCompact) std::memcpy(kindRec + 4 * t, &kinds[kind[t]], 4 * sizeof(double));  // in L1
  };
  const int both = std::min(m, pm);
  for (int t = 0; t < both; ++t) {
    copy(t);
    ax -= fxp[t]; ay -= fyp[t]; az -= fzp[t];
  }
  for (int t = both; t < m; ++t) copy(t);
  for (int t = both; t < pm; ++t) {
    ax -= fxp[t]; ay -= fyp[t]; az -= fzp[t];
  }
  sx = ax; sy = ay; sz = az;
  // Lanes past the last slot, up to the vector width: a finite, harmless bond (masked out later).
  for (int t = m; t < padded; ++t) {
    rec[4 * t] = xk + 1.0; rec[4 * t + 1] = yk; rec[4 * t + 2] = zk; rec[4 * t + 3] = 0.0;
    rj[t] = 0.0;
    if constexpr (kCompact) {
      kindRec[4 * t] = 1.0; kindRec[4 * t + 1] = 0.0; kindRec[4 * t + 2] = 0.0; kindRec[4 * t + 3] = 1.0;
    }
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
                                                double restLength, double invRestLength, double radiusI,
                                                double radiusJ, double stiffness, double& fjx, double& fjy,
                                                double& fjz, double& measure, double& effective) {
  BondGeometry g{};
  g.dx = dx; g.dy = dy; g.dz = dz;
  g.restLength = restLength;
  g.invRestLength = invRestLength;
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
template <class Law, class Criterion, bool kMinStretch, bool kCompact>
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
  std::uint16_t* kind = list.kind.data();
  const CentralBondList::Kind* kinds = list.kinds.data();
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
    alignas(64) double recb[4 * kChunk], rjb[kChunk];
    // The forces of a chunk (fxb[cur]...) and of the one before it, whose sums wait for the next
    // chunk's read pass (readPartners): `pending` slots of particle `owner`, its last chunk when
    // ownerDone. (sx, sy, sz): owner's sums so far.
    alignas(64) double fxb[2][kChunk], fyb[2][kChunk], fzb[2][kChunk];
    int cur = 0, pending = 0;
    std::ptrdiff_t owner = 0;
    bool ownerDone = false;
    double sx = 0, sy = 0, sz = 0;
    alignas(64) double kindb[4 * kChunk];  // the compact form's kind records
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
      double lowest = 1e300;
      const std::int32_t first = start[k], last = start[k + 1];
      if (first == last) fxOut[k] = fyOut[k] = fzOut[k] = 0.0;
      // The slots in chunks of kChunk, three passes each (see the file comment): scalar reads of
      // the partners (with the previous chunk's sums), the bond arithmetic vectorised over the
      // chunk; its sums, in slot order, come with the next chunk's reads or after the loop.
      for (std::int32_t c = first; c < last; c += kChunk) {
        const int m = std::min<std::int32_t>(kChunk, last - c);
        const int padded = (m + kLanes - 1) / kLanes * kLanes;
        // The slot streams a chunk ahead: the hardware prefetcher alone leaves the loop waiting on them.
        for (int t = 0; t < m; t += 8) {
          if constexpr (kCompact) {
            if (t % 32 == 0) __builtin_prefetch(kind + c + kChunk + t);
          } else {
            __builtin_prefetch(L0 + c + kChunk + t);
            __builtin_prefetch(kb + c + kChunk + t);
            __builtin_prefetch(limit + c + kChunk + t);
          }
          if (t % 16 == 0) __builtin_prefetch(partner + c + kChunk + t);
        }
        detail::readPartners<kRadii, kCompact>(partner + c, kCompact ? kind + c : nullptr, kinds, m, padded, packed,
                                               rad, xk, yk, zk, recb, rjb, kindb, fxb[cur ^ 1], fyb[cur ^ 1],
                                               fzb[cur ^ 1], pending, sx, sy, sz);
        if (ownerDone) {
          fxOut[owner] = sx; fyOut[owner] = sy; fzOut[owner] = sz;
          sx = sy = sz = 0.0;
        }
        // Whether a bond of the chunk breaks now, as an OR: a `+` reduction of the same flag lost
        // counts here (GCC 12, 512-bit vectors) and left breaking bonds unmarked.
        std::int64_t chunkBreaks = 0;
#pragma omp simd reduction(| : chunkBreaks) reduction(min : lowest)
        for (int t = 0; t < padded; ++t) {
          // A whole number of vectors, no scalar remainder: the lanes past m read no slot data and
          // keep nothing.
          const bool inside = t < m;
          // The chunk's rest length, its reciprocal, stiffness and threshold: the kind records
          // (compact form: 1/L0 computed once per kind, no division per slot) or the slot streams
          // (full form: 1/L0 divided here, the same correctly rounded number as the kind table's and
          // the generic loop's 1.0 / L0; a fourth per-slot stream would cost more than it saves).
          double restLength, invRestLength, stiffness, threshold;
          if constexpr (kCompact) {
            restLength = kindb[4 * t]; invRestLength = kindb[4 * t + 3]; stiffness = kindb[4 * t + 1];
            threshold = inside ? kindb[4 * t + 2] : kBroken;
          } else {
            restLength = inside ? L0[c + t] : 1.0;
            invRestLength = 1.0 / restLength;
            stiffness = inside ? kb[c + t] : 0.0;
            threshold = inside ? limit[c + t] : kBroken;
          }
          double fjx, fjy, fjz, measure, effective;
          detail::evaluateSlot(lawCopy, crit, recb[4 * t] - xk, recb[4 * t + 1] - yk, recb[4 * t + 2] - zk,
                               restLength, invRestLength, kRadii ? rk : 0.0, kRadii ? rjb[t] : 0.0, stiffness,
                               fjx, fjy, fjz, measure, effective);
          if constexpr (kMinStretch) effective += crit.alpha * std::max(sk, recb[4 * t + 3]);
          const bool keep = effective < threshold;
          chunkBreaks |= static_cast<std::int64_t>(!keep) & static_cast<std::int64_t>(threshold != kBroken);
          keepb[t] = keep ? 1 : 0;
          // Force on k = −(force on the partner), as the generic gather adds it.
          fxb[cur][t] = keep ? fjx : 0.0; fyb[cur][t] = keep ? fjy : 0.0; fzb[cur][t] = keep ? fjz : 0.0;
          lowest = keep ? std::min(lowest, measure) : lowest;
        }
        pending = m; owner = k; ownerDone = c + kChunk >= last;
        cur ^= 1;
        if (chunkBreaks > 0) {
          for (int t = 0; t < m; ++t) {
            const std::int32_t s = c + t;
            if (keepb[t] || (kCompact ? kindb[4 * t + 2] : limit[s]) == kBroken) continue;
            if constexpr (kCompact)
              kind[s] = CentralBondList::kBrokenKind;
            else
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
      if constexpr (kMinStretch) minNext[k] = lowest < 1e300 ? lowest : sk;
    }
    // The thread's last chunk's sums (its particles are its own: no other thread writes them).
    if (pending > 0) {
      for (int t = 0; t < pending; ++t) {
        sx -= fxb[cur ^ 1][t]; sy -= fyb[cur ^ 1][t]; sz -= fzb[cur ^ 1][t];
      }
      fxOut[owner] = sx; fyOut[owner] = sy; fzOut[owner] = sz;
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
