#include "sph/fluid_rates.hpp"

#include <algorithm>
#include <cmath>

#if defined(__AVX512F__) && defined(__AVX512VL__) && !defined(RUPTURE_SPH_NO_INTRINSICS)
// GCC 12 reports its own intrinsics' undefined pass-through operands as maybe-uninitialized
// (a known false positive of GCC 12); the state at the header's lines is what counts.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#define RUPTURE_SPH_AVX512 1
#endif

#include "core/parallel.hpp"

namespace rupture::sph {

namespace {

using Packed = RateWorkspace::Packed;

/// Constants of the pair loop.
struct PairConstants {
  double h, twoH, eta2, support2, alphaC0, beta, kx, ky, kz, diffusionScale, uniformMass;
  // The cubic spline's F = (dW/dr)/r = kF (4 max(h − r, 0)² − (2h − r)²)/r for r < 2h, kF = 0.75 a_D/h³:
  // one expression for both pieces, so no branch.
  double kF;
  double halfAlphaC0, halfBeta;  // ½ α c0, ½ β: the ½ of 1/ρ̄ = ½ (1/ρ_a + 1/ρ_b) folded in
};

/// Neighbours handled per block of the pair loop: their fields are copied into contiguous arrays
/// (the gather), the pair terms computed by one vector loop over them, then added to the
/// neighbours' accumulators by a scalar loop (the scatter). 32 keeps the block's arrays in L1.
constexpr int kBlock = 32;

/// The pairs of fluid particle i with list[begin, end): each pair once, added to i's sums (`own`)
/// and to the neighbour's accumulator acc[4 (j − lo) …]: ax, ay, az, dρ/dt. With UniformMass the
/// sums are per unit mass (the caller multiplies by the mass): 6 multiplications fewer per pair.
/// Diffuse: add the δ-SPH term (fluid–fluid pairs). Skin pairs (r ≥ 2h) are computed with F = 0,
/// so the vector loop has no branch.
template <bool Diffuse, bool UniformMass>
[[gnu::always_inline]] inline void pairsOf(std::size_t i, const std::int32_t* __restrict list, int begin, int end,
                                           const Packed* __restrict pk, const double* __restrict rho,
                                           const double* __restrict mass, double* __restrict acc, std::size_t lo,
                                           const PairConstants& k, double own[4], double& maxMu) {
  const Packed a = pk[i];
  const double rhoi = rho[i], mi = UniformMass ? 1.0 : mass[i];
  double sax = 0, say = 0, saz = 0, sdrho = 0, smu = maxMu;
  alignas(64) double ox[kBlock], oy[kBlock], oz[kBlock], od[kBlock];
  for (int n0 = begin; n0 < end; n0 += kBlock) {
    const int m = std::min(kBlock, end - n0);
    const std::int32_t* __restrict nb = list + n0;
#pragma omp simd reduction(+ : sax, say, saz, sdrho) reduction(max : smu)
    for (int q = 0; q < m; ++q) {
      const Packed& b = pk[nb[q]];
      const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
      const double r2 = dx * dx + dy * dy + dz * dz;
      const bool inside = r2 < k.support2;  // a skin pair contributes nothing
      const double r = std::sqrt(r2 > 1e-300 ? r2 : 1e-300);
      const double s = k.h - r > 0.0 ? k.h - r : 0.0, t = k.twoH - r;
      const double F = inside ? k.kF * (4.0 * s * s - t * t) / r : 0.0;
      const double dvx = a.vx - b.vx, dvy = a.vy - b.vy, dvz = a.vz - b.vz;
      const double vr = dvx * dx + dvy * dy + dvz * dz;
      const double mu = k.h * vr / (r2 + k.eta2);
      // Π only for approaching pairs (μ < 0), as min(μ, 0).
      // 1/ρ̄ as the mean of 1/ρ: equal to 2/(ρ_a + ρ_b) to O((Δρ/ρ)²), 1e-4 here, without a division.
      const double approach = mu < 0.0 ? mu : 0.0;
      const double viscous = approach * (k.halfBeta * approach - k.halfAlphaC0) * (a.inverseRho + b.inverseRho);
      const double mj = UniformMass ? 1.0 : mass[nb[q]];
      const double c = (a.pressureOverRho2 + b.pressureOverRho2 + viscous) * F;
      const double fx = c * dx, fy = c * dy, fz = c * dz;
      const double continuity = F * vr;
      sax -= mj * fx;
      say -= mj * fy;
      saz -= mj * fz;
      ox[q] = mi * fx;
      oy[q] = mi * fy;
      oz[q] = mi * fz;
      if constexpr (Diffuse) {
        const double d = ((rhoi - rho[nb[q]]) - (k.kx * dx + k.ky * dy + k.kz * dz)) * F * k.diffusionScale;
        sdrho += mj * (continuity + d * b.inverseRho);
        od[q] = mi * (continuity - d * a.inverseRho);
      } else {
        sdrho += mj * continuity;
        od[q] = mi * continuity;
      }
      const double amu = inside ? std::fabs(mu) : 0.0;
      smu = smu > amu ? smu : amu;
    }
    for (int q = 0; q < m; ++q) {
      double* __restrict aj = acc + 4 * (static_cast<std::size_t>(nb[q]) - lo);
      aj[0] += ox[q];
      aj[1] += oy[q];
      aj[2] += oz[q];
      aj[3] += od[q];
    }
  }
  own[0] += sax;
  own[1] += say;
  own[2] += saz;
  own[3] += sdrho;
  maxMu = smu;
}

#ifdef RUPTURE_SPH_AVX512
/// How far ahead in the neighbour list the AVX-512 loop prefetches (entries).
constexpr int kPrefetch = 16;
static_assert(kPrefetch + 8 <= NeighbourList::kListPadding, "the loop reads up to kPrefetch + 8 entries past a list");

/// 1/√x (x > 0) from the 14-bit estimate and two Newton steps: 14 → 28 → full double precision
/// (a few ulp), several times cheaper than vsqrtpd and vdivpd on 512-bit vectors.
inline __m512d inverseSqrt(__m512d x) {
  const __m512d half = _mm512_set1_pd(0.5), threeHalves = _mm512_set1_pd(1.5);
  const __m512d hx = _mm512_mul_pd(half, x);
  __m512d y = _mm512_rsqrt14_pd(x);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hx, _mm512_mul_pd(y, y), threeHalves));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hx, _mm512_mul_pd(y, y), threeHalves));
  return y;
}

/// 1/x (x > 0): the 14-bit estimate and two Newton steps.
inline __m512d inverse(__m512d x) {
  const __m512d two = _mm512_set1_pd(2.0);
  __m512d y = _mm512_rcp14_pd(x);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(x, y, two));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(x, y, two));
  return y;
}

/// The 8 records pk[jj[0..7]] as 8 columns (lane l = record l): each 64-byte record is loaded whole
/// and the 8 × 8 block transposed (24 shuffles: cheaper than 8 gathers).
struct Columns {
  __m512d x, y, z, pressureOverRho2, vx, vy, vz, inverseRho;
};
[[gnu::always_inline]] inline Columns loadColumns(const Packed* __restrict pk, const std::int32_t* jj) {
  // Transposition indices (permutex2var: 0–7 the first operand, 8–15 the second).
  const __m512i lowPairs = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
  const __m512i highPairs = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  // Rows: the 8 records [x y z p/ρ² vx vy vz 1/ρ].
  __m512d r[8];
  for (int l = 0; l < 8; ++l) r[l] = _mm512_load_pd(&pk[jj[l]].x);
  __m512d t[8];
  for (int l = 0; l < 4; ++l) {
    t[2 * l] = _mm512_unpacklo_pd(r[2 * l], r[2 * l + 1]);     // x z vx vz of rows 2l, 2l+1
    t[2 * l + 1] = _mm512_unpackhi_pd(r[2 * l], r[2 * l + 1]); // y p vy 1/ρ
  }
  const __m512d u0 = _mm512_permutex2var_pd(t[0], lowPairs, t[2]);   // x0-3 vx0-3
  const __m512d u1 = _mm512_permutex2var_pd(t[0], highPairs, t[2]);  // z0-3 vz0-3
  const __m512d u2 = _mm512_permutex2var_pd(t[1], lowPairs, t[3]);   // y0-3 vy0-3
  const __m512d u3 = _mm512_permutex2var_pd(t[1], highPairs, t[3]);  // p0-3 ir0-3
  const __m512d u4 = _mm512_permutex2var_pd(t[4], lowPairs, t[6]);
  const __m512d u5 = _mm512_permutex2var_pd(t[4], highPairs, t[6]);
  const __m512d u6 = _mm512_permutex2var_pd(t[5], lowPairs, t[7]);
  const __m512d u7 = _mm512_permutex2var_pd(t[5], highPairs, t[7]);
  return {_mm512_shuffle_f64x2(u0, u4, 0x44), _mm512_shuffle_f64x2(u2, u6, 0x44), _mm512_shuffle_f64x2(u1, u5, 0x44),
          _mm512_shuffle_f64x2(u3, u7, 0x44), _mm512_shuffle_f64x2(u0, u4, 0xEE), _mm512_shuffle_f64x2(u2, u6, 0xEE),
          _mm512_shuffle_f64x2(u1, u5, 0xEE), _mm512_shuffle_f64x2(u3, u7, 0xEE)};
}

/// pairsOf on 8 neighbours at a time. The 8 neighbours' 64-byte records are loaded whole and
/// transposed (8 × 8 doubles, 24 shuffles: cheaper than 8 gathers), the pair terms computed in
/// vectors (a lane of a partial block or a skin pair gets F = 0), and the 8 results transposed back
/// into (ax, ay, az, dρ/dt) quadruples added to the neighbours' accumulators, one 256-bit
/// load-add-store each. The neighbours of one particle are distinct, so the 8 updates of a block
/// never meet. The sums are deterministic (fixed lane order), whatever the thread count.
template <bool Diffuse, bool UniformMass>
[[gnu::always_inline]] inline void pairsOfAvx512(std::size_t i, const std::int32_t* __restrict list, int begin,
                                                 int end, const Packed* __restrict pk, const double* __restrict rho,
                                                 const double* __restrict mass, double* __restrict acc, std::size_t lo,
                                                 const PairConstants& k, double own[4], double& maxMu) {
  const Packed& a = pk[i];
  const __m512d ax = _mm512_set1_pd(a.x), ay = _mm512_set1_pd(a.y), az = _mm512_set1_pd(a.z);
  const __m512d avx = _mm512_set1_pd(a.vx), avy = _mm512_set1_pd(a.vy), avz = _mm512_set1_pd(a.vz);
  const __m512d ap = _mm512_set1_pd(a.pressureOverRho2), air = _mm512_set1_pd(a.inverseRho);
  const __m512d support2 = _mm512_set1_pd(k.support2), tiny = _mm512_set1_pd(1e-300);
  const __m512d h = _mm512_set1_pd(k.h), twoH = _mm512_set1_pd(k.twoH), kF = _mm512_set1_pd(k.kF);
  const __m512d eta2 = _mm512_set1_pd(k.eta2), four = _mm512_set1_pd(4.0), zero = _mm512_setzero_pd();
  const __m512d halfBeta = _mm512_set1_pd(k.halfBeta), halfAlphaC0 = _mm512_set1_pd(k.halfAlphaC0);
  const __m512d mi = _mm512_set1_pd(UniformMass ? 1.0 : mass[i]);
  // Transposition indices back to quadruples (permutex2var: 0–7 the first operand, 8–15 the second).
  const __m512i quadLow = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11);
  const __m512i quadHigh = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
  __m512d sax = zero, say = zero, saz = zero, sdrho = zero, smu = zero;
  for (int n0 = begin; n0 < end; n0 += 8) {
    const int m = std::min(8, end - n0);
    const __mmask8 valid = static_cast<__mmask8>((1u << m) - 1u);
    // Lanes past the end read the next list's entries (or the padding): valid particles, their F
    // masked to 0 and their scatter skipped.
    const std::int32_t* jj = list + n0;
    const __m256i idx = _mm256_maskz_loadu_epi32(valid, jj);  // for the gathers of ρ_b and m_b
    // The records and accumulators of the neighbours kPrefetch entries ahead (they may be the next
    // particle's: the lists lie back to back, padded at the end, neighbour_list.hpp): a
    // neighbour's record is mostly in L3 (the cell-ordered sweep reuses it ~3 MB later).
    for (int l = 0; l < 8; ++l) {
      const std::int32_t ahead = list[n0 + kPrefetch + l];
      __builtin_prefetch(&pk[ahead], 0, 3);
      __builtin_prefetch(acc + 4 * (static_cast<std::size_t>(ahead) - lo), 1, 3);
    }
    const Columns b = loadColumns(pk, jj);
    const __m512d bx = b.x, by = b.y, bz = b.z, bp = b.pressureOverRho2, bvx = b.vx, bvy = b.vy, bvz = b.vz,
                  bir = b.inverseRho;
    const __m512d dx = _mm512_sub_pd(ax, bx), dy = _mm512_sub_pd(ay, by), dz = _mm512_sub_pd(az, bz);
    const __m512d r2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx)));
    const __mmask8 inside = _mm512_mask_cmp_pd_mask(valid, r2, support2, _CMP_LT_OQ);  // skin pairs: none
    const __m512d inverseR = inverseSqrt(_mm512_max_pd(r2, tiny));
    const __m512d rr = _mm512_mul_pd(_mm512_max_pd(r2, tiny), inverseR);
    const __m512d s = _mm512_max_pd(_mm512_sub_pd(h, rr), zero), tt = _mm512_sub_pd(twoH, rr);
    const __m512d spline = _mm512_fmsub_pd(_mm512_mul_pd(four, s), s, _mm512_mul_pd(tt, tt));
    const __m512d F = _mm512_maskz_mul_pd(inside, _mm512_mul_pd(kF, spline), inverseR);
    const __m512d dvx = _mm512_sub_pd(avx, bvx), dvy = _mm512_sub_pd(avy, bvy), dvz = _mm512_sub_pd(avz, bvz);
    const __m512d vr = _mm512_fmadd_pd(dvz, dz, _mm512_fmadd_pd(dvy, dy, _mm512_mul_pd(dvx, dx)));
    const __m512d mu = _mm512_mul_pd(_mm512_mul_pd(h, vr), inverse(_mm512_add_pd(r2, eta2)));
    const __m512d approach = _mm512_min_pd(mu, zero);
    const __m512d viscous = _mm512_mul_pd(_mm512_mul_pd(approach, _mm512_fmsub_pd(halfBeta, approach, halfAlphaC0)),
                                          _mm512_add_pd(air, bir));
    const __m512d c = _mm512_mul_pd(_mm512_add_pd(_mm512_add_pd(ap, bp), viscous), F);
    const __m512d fx = _mm512_mul_pd(c, dx), fy = _mm512_mul_pd(c, dy), fz = _mm512_mul_pd(c, dz);
    const __m512d continuity = _mm512_mul_pd(F, vr);
    __m512d mj = _mm512_set1_pd(1.0);
    if constexpr (!UniformMass) mj = _mm512_mask_i32gather_pd(zero, valid, idx, mass, 8);
    sax = _mm512_fnmadd_pd(mj, fx, sax);
    say = _mm512_fnmadd_pd(mj, fy, say);
    saz = _mm512_fnmadd_pd(mj, fz, saz);
    __m512d od;
    if constexpr (Diffuse) {
      const __m512d rhoj = _mm512_mask_i32gather_pd(zero, valid, idx, rho, 8);
      const __m512d hydrostatic = _mm512_fmadd_pd(_mm512_set1_pd(k.kz), dz,
                                                  _mm512_fmadd_pd(_mm512_set1_pd(k.ky), dy,
                                                                  _mm512_mul_pd(_mm512_set1_pd(k.kx), dx)));
      const __m512d d = _mm512_mul_pd(
          _mm512_mul_pd(_mm512_sub_pd(_mm512_sub_pd(_mm512_set1_pd(rho[i]), rhoj), hydrostatic), F),
          _mm512_set1_pd(k.diffusionScale));
      sdrho = _mm512_fmadd_pd(mj, _mm512_fmadd_pd(d, bir, continuity), sdrho);
      od = _mm512_fnmadd_pd(d, air, continuity);
    } else {
      sdrho = _mm512_fmadd_pd(mj, continuity, sdrho);
      od = continuity;
    }
    smu = _mm512_mask_max_pd(smu, inside, smu, _mm512_abs_pd(mu));

    // Back to one (ax, ay, az, dρ/dt) quadruple per neighbour.
    __m512d ox = fx, oy = fy, oz = fz;
    if constexpr (!UniformMass) {
      ox = _mm512_mul_pd(mi, fx);
      oy = _mm512_mul_pd(mi, fy);
      oz = _mm512_mul_pd(mi, fz);
      od = _mm512_mul_pd(mi, od);
    }
    const __m512d q0 = _mm512_unpacklo_pd(ox, oy), q1 = _mm512_unpackhi_pd(ox, oy);  // x y of lanes 0 2 4 6 / 1 3 5 7
    const __m512d q2 = _mm512_unpacklo_pd(oz, od), q3 = _mm512_unpackhi_pd(oz, od);
    const __m512d v02 = _mm512_permutex2var_pd(q0, quadLow, q2), v46 = _mm512_permutex2var_pd(q0, quadHigh, q2);
    const __m512d v13 = _mm512_permutex2var_pd(q1, quadLow, q3), v57 = _mm512_permutex2var_pd(q1, quadHigh, q3);
    const __m256d out[8] = {_mm512_castpd512_pd256(v02), _mm512_castpd512_pd256(v13),
                            _mm512_extractf64x4_pd(v02, 1), _mm512_extractf64x4_pd(v13, 1),
                            _mm512_castpd512_pd256(v46), _mm512_castpd512_pd256(v57),
                            _mm512_extractf64x4_pd(v46, 1), _mm512_extractf64x4_pd(v57, 1)};
    auto scatter = [&](int l) {
      double* aj = acc + 4 * (static_cast<std::size_t>(jj[l]) - lo);
      _mm256_storeu_pd(aj, _mm256_add_pd(_mm256_loadu_pd(aj), out[l]));
    };
    if (m == 8) {
      for (int l = 0; l < 8; ++l) scatter(l);
    } else {
      for (int l = 0; l < m; ++l) scatter(l);
    }
  }
  own[0] += _mm512_reduce_add_pd(sax);
  own[1] += _mm512_reduce_add_pd(say);
  own[2] += _mm512_reduce_add_pd(saz);
  own[3] += _mm512_reduce_add_pd(sdrho);
  maxMu = std::max(maxMu, _mm512_reduce_max_pd(smu));
}
#endif

/// The Shepard sums of a boundary particle at (xw, yw, zw) over its fluid neighbours (Adami et al.
/// 2012, eq. 27): Σ W, Σ p_f W and Σ ρ_f (g·x_wf) W, read from the fluid's records (ρ_f = 1/(1/ρ)_f,
/// p_f = (p/ρ²)_f ρ_f²). Neighbours in the skin (r >= 2h) add nothing.
struct WallSums {
  CubicSplineKernel kernel;
  double gx, gy, gz;

  [[gnu::always_inline]] void operator()(double xw, double yw, double zw, const std::int32_t* __restrict list, int count,
                                         const Packed* __restrict pk, double& sumW, double& sumPW, double& sumRhoRW) const {
#ifdef RUPTURE_SPH_AVX512
    // 8 neighbours at a time from their records (loadColumns); lanes past the end read the next
    // list's entries or the padding (valid particles) and are masked out.
    const double h = kernel.h();
    const __m512d vxw = _mm512_set1_pd(xw), vyw = _mm512_set1_pd(yw), vzw = _mm512_set1_pd(zw);
    const __m512d invH = _mm512_set1_pd(1.0 / h), two = _mm512_set1_pd(2.0), one = _mm512_set1_pd(1.0);
    const __m512d tiny = _mm512_set1_pd(1e-300), aD = _mm512_set1_pd(kernel.normalisation());
    const __m512d vgx = _mm512_set1_pd(gx), vgy = _mm512_set1_pd(gy), vgz = _mm512_set1_pd(gz);
    __m512d sW = _mm512_setzero_pd(), sPW = _mm512_setzero_pd(), sRR = _mm512_setzero_pd();
    for (int n0 = 0; n0 < count; n0 += 8) {
      const int m = std::min(8, count - n0);
      const __mmask8 valid = static_cast<__mmask8>((1u << m) - 1u);
      const Columns f = loadColumns(pk, list + n0);
      const __m512d dx = _mm512_sub_pd(vxw, f.x), dy = _mm512_sub_pd(vyw, f.y), dz = _mm512_sub_pd(vzw, f.z);
      const __m512d r2 = _mm512_max_pd(_mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx))), tiny);
      const __m512d q = _mm512_mul_pd(_mm512_mul_pd(r2, inverseSqrt(r2)), invH);
      const __mmask8 inside = _mm512_mask_cmp_pd_mask(valid, q, two, _CMP_LT_OQ);
      // w = 1 − 1.5 q² + 0.75 q³ (q < 1), 0.25 (2 − q)³ (1 <= q < 2).
      const __m512d q2 = _mm512_mul_pd(q, q);
      const __m512d nearW = _mm512_fmadd_pd(q2, _mm512_fmsub_pd(_mm512_set1_pd(0.75), q, _mm512_set1_pd(1.5)), one);
      const __m512d t = _mm512_sub_pd(two, q);
      const __m512d farW = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(0.25), t), _mm512_mul_pd(t, t));
      const __mmask8 isNear = _mm512_cmp_pd_mask(q, one, _CMP_LT_OQ);
      const __m512d W = _mm512_maskz_mul_pd(inside, aD, _mm512_mask_blend_pd(isNear, farW, nearW));
      const __m512d rho = inverse(f.inverseRho);
      const __m512d pressure = _mm512_mul_pd(_mm512_mul_pd(f.pressureOverRho2, rho), rho);
      const __m512d gr = _mm512_fmadd_pd(vgz, dz, _mm512_fmadd_pd(vgy, dy, _mm512_mul_pd(vgx, dx)));
      sW = _mm512_add_pd(sW, W);
      sPW = _mm512_fmadd_pd(pressure, W, sPW);
      sRR = _mm512_fmadd_pd(_mm512_mul_pd(rho, gr), W, sRR);  // (g − a_w)·Σ ρ_f x_wf W, a_w neglected
    }
    sumW = _mm512_reduce_add_pd(sW);
    sumPW = _mm512_reduce_add_pd(sPW);
    sumRhoRW = _mm512_reduce_add_pd(sRR);
#else
    sumW = sumPW = sumRhoRW = 0;
    for (int m = 0; m < count; ++m) {
      const Packed& f = pk[list[m]];
      const double dx = xw - f.x, dy = yw - f.y, dz = zw - f.z;
      const double W = kernel.value(std::sqrt(dx * dx + dy * dy + dz * dz));
      const double rho = 1.0 / f.inverseRho;
      sumW += W;
      sumPW += f.pressureOverRho2 * rho * rho * W;
      sumRhoRW += rho * (gx * dx + gy * dy + gz * dz) * W;  // (g − a_w)·Σ ρ_f x_wf W, a_w neglected
    }
#endif
  }
};

/// Particle a's record from its estimates, pressure (Pa) and 1/ρ (m³/kg); 2D: z and v_z are 0.
Packed recordOf(const FluidParticles& p, std::size_t a, double pressure, double inverseRho, bool is3d) {
  return {p.x[a], p.y[a], is3d ? p.z[a] : 0.0, pressure * inverseRho * inverseRho,
          p.vxEst[a], p.vyEst[a], is3d ? p.vzEst[a] : 0.0, inverseRho};
}

}  // namespace

RateExtremes computeRates(FluidParticles& p, const NeighbourList& list, const FluidModel& model,
                          RateWorkspace& ws, const RateClosing& closing) {
  const std::size_t n = p.size();
  const EquationOfState eos = model.eos;
  const CubicSplineKernel kernel = model.kernel();
  const bool is3d = model.dimension == 3;
  const bool diffuse = model.diffusion != DiffusionModel::Off && model.delta > 0;
  PairConstants k{};
  k.h = kernel.h();
  k.twoH = 2.0 * k.h;
  k.kF = 0.75 * kernel.normalisation() / (k.h * k.h * k.h);
  k.eta2 = 0.01 * k.h * k.h;
  k.support2 = kernel.support() * kernel.support();
  k.alphaC0 = model.alpha * eos.soundSpeed;
  k.beta = model.beta;
  k.halfAlphaC0 = 0.5 * k.alphaC0;
  k.halfBeta = 0.5 * k.beta;
  // Fourtakas: ρ_a − ρ_b minus its hydrostatic part ρ0 g·x_ab/c0² (acoustic linearisation).
  if (model.diffusion == DiffusionModel::Fourtakas) {
    const double s = eos.referenceDensity / (eos.soundSpeed * eos.soundSpeed);
    k.kx = s * model.gravity[0];
    k.ky = s * model.gravity[1];
    k.kz = s * model.gravity[2];
  }
  k.diffusionScale = 2.0 * model.delta * kernel.h() * eos.soundSpeed;

  // 1. Fluid: pressure from the equation of state, and the record the pair loop reads (one cache
  //    line: position, p/ρ², velocity estimate, 1/ρ). Equal masses (every lattice-built set) save
  //    the pair loop a load per pair; checked here, over every particle. Dynamic, as the fluid is
  //    not spread evenly over the cell-ordered particles.
  ws.packed.resize(n);
  Packed* packed = ws.packed.data();
  double minMass = n > 0 ? p.mass[0] : 0.0, maxMass = minMass;
#pragma omp parallel for schedule(dynamic, 4096) reduction(min : minMass) reduction(max : maxMass) if (worthParallel(n))
  for (std::size_t a = 0; a < n; ++a) {
    minMass = std::min(minMass, p.mass[a]);
    maxMass = std::max(maxMass, p.mass[a]);
    if (p.body[a] != kFluid) continue;
    const double pressure = eos.pressure(p.rhoEst[a]), inverseRho = 1.0 / p.rhoEst[a];
    p.pressure[a] = pressure;
    packed[a] = recordOf(p, a, pressure, inverseRho, is3d);
  }
  // 2. Boundary particles: the pressure extrapolated from the fluid around them (Adami et al. 2012,
  //    eq. 27), their density its EOS inverse, and their record.
  const double gx = model.gravity[0], gy = model.gravity[1], gz = model.gravity[2];
  const WallSums wallSums{kernel, gx, gy, gz};
#pragma omp parallel for schedule(dynamic, 256) if (worthParallel(n))
  for (std::size_t w = 0; w < n; ++w) {
    if (p.body[w] == kFluid) continue;
    const double xw = p.x[w], yw = p.y[w], zw = is3d ? p.z[w] : 0.0;
    double sumW = 0, sumPW = 0, sumRhoRW = 0;
    if (list.count(w) > 0) wallSums(xw, yw, zw, list.neighbours(w), list.count(w), packed, sumW, sumPW, sumRhoRW);
    // A wall holds no tension: fluid leaving it must not be pulled back (as DualSPHysics' ρ_w >= ρ0).
    const double pw = sumW > 0 ? std::max(0.0, (sumPW + sumRhoRW) / sumW) : 0.0;
    const double rhow = pw > 0 ? eos.density(pw) : eos.referenceDensity, inverseRho = 1.0 / rhow;
    p.pressure[w] = pw;
    p.rhoEst[w] = rhow;
    packed[w] = recordOf(p, w, pw, inverseRho, is3d);
  }

  k.uniformMass = minMass;
  const bool uniform = minMass == maxMass;

  // Each chunk sums its pairs into its own buffer (the particles it touches).
  const std::vector<NeighbourList::Chunk>& chunks = list.chunks();
  std::vector<std::size_t> offset(chunks.size() + 1, 0);
  for (std::size_t c = 0; c < chunks.size(); ++c) offset[c + 1] = offset[c] + 4 * chunks[c].touched();
  if (ws.sums.size() < offset.back()) ws.sums.resize(offset.back());
  const Packed* pk = ws.packed.data();
  const double* rho = p.rhoEst.data();
  const double* mass = p.mass.data();
  double maxMu = 0;
  auto chunkLoop = [&]<bool Uniform>() {
#pragma omp parallel for schedule(dynamic, 1) reduction(max : maxMu) if (chunks.size() > 1)
    for (std::size_t c = 0; c < chunks.size(); ++c) {
      const NeighbourList::Chunk& ch = chunks[c];
      double* acc = ws.sums.data() + offset[c];
      // Zeroed here, just before its sums, rather than by the reduction after reading it: the
      // reduction then only reads, and no line of zeros goes back to memory (memory-bound on W3).
      std::fill(acc, acc + 4 * ch.touched(), 0.0);
      double mu = 0;
      for (std::size_t i = ch.begin; i < ch.end; ++i) {
        if (p.body[i] != kFluid) continue;
        const std::int32_t* nb = list.neighbours(i);
        const int nf = list.fluidCount(i), total = list.count(i);
        double own[4] = {0, 0, 0, 0};
#ifdef RUPTURE_SPH_AVX512
        // Without diffusion, fluid and wall neighbours in one run: fewer partial blocks of 8.
        if (diffuse) {
          pairsOfAvx512<true, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, ch.lo, k, own, mu);
          pairsOfAvx512<false, Uniform>(i, nb, nf, total, pk, rho, mass, acc, ch.lo, k, own, mu);
        } else {
          pairsOfAvx512<false, Uniform>(i, nb, 0, total, pk, rho, mass, acc, ch.lo, k, own, mu);
        }
#else
        if (diffuse) pairsOf<true, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, ch.lo, k, own, mu);
        else pairsOf<false, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, ch.lo, k, own, mu);
        pairsOf<false, Uniform>(i, nb, nf, total, pk, rho, mass, acc, ch.lo, k, own, mu);
#endif
        double* ai = acc + 4 * (i - ch.lo);
        for (int a = 0; a < 4; ++a) ai[a] += own[a];
      }
      maxMu = std::max(maxMu, mu);
    }
  };
  if (uniform) chunkLoop.template operator()<true>();
  else chunkLoop.template operator()<false>();

  // The chunks' buffers added in chunk order: the same sums for any thread count. By spans of
  // particles, each chunk's overlap with the span added as one contiguous (vectorised) run.
  const double massScale = uniform ? k.uniformMass : 1.0;
  const double tau = closing.halfKick;
  const std::size_t bodies = closing.bodyForces.size();
  double maxAcc2 = 0, maxRho = 0;
  constexpr std::size_t kSpan = 512;
  const std::size_t spans = (n + kSpan - 1) / kSpan;
  ws.spanForces.resize(3 * bodies * spans);
#pragma omp parallel for schedule(static) reduction(max : maxAcc2, maxRho) if (worthParallel(n))
  for (std::size_t b = 0; b < spans; ++b) {
    const std::size_t a0 = b * kSpan, a1 = std::min(n, a0 + kSpan);
    double* __restrict spanForce = ws.spanForces.data() + 3 * bodies * b;
    std::fill(spanForce, spanForce + 3 * bodies, 0.0);
    alignas(64) double s[4 * kSpan];
    std::fill(s, s + 4 * (a1 - a0), 0.0);
    for (std::size_t c = 0; c < chunks.size(); ++c) {
      const NeighbourList::Chunk& ch = chunks[c];
      if (ch.touched() == 0) continue;
      const std::size_t from = std::max(a0, ch.lo), to = std::min(a1, ch.hi + 1);
      if (from >= to) continue;
      const double* __restrict v = ws.sums.data() + offset[c] + 4 * (from - ch.lo);
      double* __restrict d = s + 4 * (from - a0);
      for (std::size_t m = 0; m < 4 * (to - from); ++m) d[m] += v[m];
    }
    for (std::size_t a = a0; a < a1; ++a) {
      const double* t = s + 4 * (a - a0);
      p.ax[a] = massScale * t[0];
      p.ay[a] = massScale * t[1];
      p.az[a] = massScale * t[2];
      const std::int32_t body = p.body[a];
      if (body == kFluid) {
        p.drho[a] = massScale * t[3];
        const double fx = p.ax[a] + gx, fy = p.ay[a] + gy, fz = p.az[a] + gz;
        maxAcc2 = std::max(maxAcc2, fx * fx + fy * fy + fz * fz);
        maxRho = std::max(maxRho, p.rhoEst[a]);
        if (tau != 0) {
          p.vx[a] += tau * fx;
          p.vy[a] += tau * fy;
          p.vz[a] += tau * fz;
          p.rho[a] += tau * p.drho[a];
        }
      } else {
        p.drho[a] = 0;  // boundary densities are extrapolated, not integrated
        if (tau != 0) p.rho[a] = p.rhoEst[a];
        if (bodies > 0) {
          const double m = p.mass[a];
          double* f = spanForce + 3 * static_cast<std::size_t>(body);
          f[0] += m * p.ax[a];
          f[1] += m * p.ay[a];
          f[2] += m * p.az[a];
        }
      }
    }
  }
  for (std::size_t body = 0; body < bodies; ++body) {
    std::array<double, 3> f{0, 0, 0};
    for (std::size_t b = 0; b < spans; ++b)
      for (int c = 0; c < 3; ++c) f[c] += ws.spanForces[3 * (bodies * b + body) + c];
    closing.bodyForces[body] = f;
  }
  return {maxMu, std::sqrt(maxAcc2), maxRho};
}

}  // namespace rupture::sph
