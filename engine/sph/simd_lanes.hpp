#pragma once
// The vector widths the SPH pair loops run at: with AVX-512, 8 doubles (512-bit registers) or 4
// (256-bit registers, with AVX-512VL's masks and estimates); with AVX2 and FMA only, 4 (256-bit
// registers, masks as vectors of all-ones lanes, exact roots and divisions). The AVX-512 widths
// give the same lane arithmetic, so a loop written once over `Lanes` computes bitwise the same
// results at either width (the sums of 8 lanes are combined in one fixed order, sumOfHalves). Which
// width is faster depends on the processor: Zen 4 runs 512-bit instructions on 256-bit units, so a
// 512-bit shuffle costs it two, and the 24 shuffles that transpose 8 records outweigh the 16 that
// transpose 4 twice; processors with 512-bit units prefer 8 (preferredLaneWidth). The AVX2 lanes
// (Zen 3, processors without AVX-512) share the 4-wide loads, transpositions and sums, but take r,
// 1/r and 1/(r² + η²) from the divider (AVX2 has no double-precision estimates): the same terms
// correctly rounded, so their results agree with the AVX-512 lanes' to round-off, not bit for bit.
#include <cstddef>
#include <cstdint>

#if !defined(RUPTURE_SPH_NO_INTRINSICS) && defined(__AVX2__) && defined(__FMA__)
// GCC 12 reports its own intrinsics' undefined pass-through operands (_mm512_undefined_pd) as
// uninitialized (a known false positive of GCC 12); the state at the header's lines is what counts.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#define RUPTURE_SPH_AVX2 1  // the 4-wide lanes (every AVX-512 processor has AVX2 and FMA too)
#if defined(__AVX512F__) && defined(__AVX512VL__)
#define RUPTURE_SPH_AVX512 1
#endif
#endif

namespace rupture::sph {

/// The lane width the SPH pair loops are asked for: 4 or 8 doubles, or kPortableLanes for the
/// portable loops (an `omp simd` loop over blocks of neighbours and a scalar scatter, every build).
inline constexpr int kPortableLanes = 1;

/// The width the pair loops use on this processor: RUPTURE_SPH_LANES (1, 4 or 8; any other value
/// is ignored) if set, else 4 on AMD family 19h (Zen 3 and Zen 4; Zen 4's 512-bit instructions are
/// split in two 256-bit halves), 8 elsewhere. Read once. A build without AVX-512 runs 8 as 4, and
/// one without AVX2 and FMA (or with RUPTURE_SPH_NO_INTRINSICS) runs the portable loops whatever
/// the width.
int preferredLaneWidth();

#ifdef RUPTURE_SPH_AVX2

/// What the widths share: GCC's vector types (__m512d, __m256d: Width doubles) take the
/// arithmetic operators and a scalar operand as a broadcast, as the _mm*_add_pd… intrinsics are
/// defined. (By width, not by type: a template argument would drop the types' may_alias.)
template <int Width>
struct VectorOf;
template <>
struct VectorOf<4> {
  using type = __m256d;
};
#ifdef RUPTURE_SPH_AVX512
template <>
struct VectorOf<8> {
  using type = __m512d;
};
#endif

template <int Width>
struct LaneArithmetic {
  using Vec = typename VectorOf<Width>::type;
  /// What the pair loops read of a neighbour, as 8 columns of lanes (lane l = neighbour l).
  struct Columns {
    Vec x, y, z, pressureOverRho2, vx, vy, vz, inverseRho;
  };
  static Vec set1(double v) { return Vec{} + v; }
  static Vec zero() { return Vec{}; }
  static Vec add(Vec a, Vec b) { return a + b; }
  static Vec sub(Vec a, Vec b) { return a - b; }
  static Vec mul(Vec a, Vec b) { return a * b; }
};

/// The sum of 8 lanes held as two halves of 4 (lanes l and l + 4 first, then the two 128-bit
/// halves, then the two lanes left): the one order of every width.
inline double sumOfHalves(__m256d low, __m256d high) {
  const __m256d s = _mm256_add_pd(high, low);
  const __m128d t = _mm_add_pd(_mm256_extractf128_pd(s, 1), _mm256_castpd256_pd128(s));
  return _mm_cvtsd_f64(_mm_add_sd(t, _mm_unpackhi_pd(t, t)));
}

/// acc[4 (j[l] − lo) …] += out[l] for the first m lanes: one 256-bit load-add-store each.
template <int Width>
[[gnu::always_inline]] inline void addQuadruplesEach(double* __restrict acc, std::size_t lo, const std::int32_t* j,
                                                     int m, const __m256d (&out)[Width]) {
  auto add = [&](int l) {
    double* a = acc + 4 * (static_cast<std::size_t>(j[l]) - lo);
    _mm256_storeu_pd(a, _mm256_add_pd(_mm256_loadu_pd(a), out[l]));
  };
  if (m == Width) {
    for (int l = 0; l < Width; ++l) add(l);
  } else {
    for (int l = 0; l < m; ++l) add(l);
  }
}

/// 4 lanes in one 256-bit register: what needs AVX2 and FMA only (the masks, estimates and
/// gathers are the derived types'). A loop over neighbours in blocks of 8 runs two of these per
/// block, lanes 0–3 and 4–7, each summing into its own half: so the sums are Lanes8's.
struct Lanes256 : LaneArithmetic<4> {
  static constexpr int kWidth = 4;
  using Index = __m128i;

  static Vec min(Vec a, Vec b) { return _mm256_min_pd(a, b); }
  static Vec max(Vec a, Vec b) { return _mm256_max_pd(a, b); }
  static Vec abs(Vec a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
  static Vec fmadd(Vec a, Vec b, Vec c) { return _mm256_fmadd_pd(a, b, c); }   // a b + c
  static Vec fmsub(Vec a, Vec b, Vec c) { return _mm256_fmsub_pd(a, b, c); }   // a b − c
  static Vec fnmadd(Vec a, Vec b, Vec c) { return _mm256_fnmadd_pd(a, b, c); } // c − a b
  /// Σ of lanes 0–3 of parts[0] and 4–7 of parts[1], in Lanes8's order.
  static double reduceAdd(const Vec* parts) { return sumOfHalves(parts[0], parts[1]); }
  static double reduceMax(Vec a) {
    const __m128d t = _mm_max_pd(_mm256_extractf128_pd(a, 1), _mm256_castpd256_pd128(a));
    return _mm_cvtsd_f64(_mm_max_sd(t, _mm_unpackhi_pd(t, t)));
  }

  /// The 4 records' columns: x y of records 0 and 2 in one register and of 1 and 3 in another
  /// (two 128-bit loads each), then one unpack per column (8 inserts and 8 unpacks in all).
  template <class Record>
  [[gnu::always_inline]] static Columns columns(const Record* __restrict rec, const std::int32_t* j) {
    const double* r0 = &rec[j[0]].x;
    const double* r1 = &rec[j[1]].x;
    const double* r2 = &rec[j[2]].x;
    const double* r3 = &rec[j[3]].x;
    Vec c[8];
    for (int f = 0; f < 8; f += 2) {
      const __m256d even = _mm256_loadu2_m128d(r2 + f, r0 + f);  // [f f+1] of records 0, 2
      const __m256d odd = _mm256_loadu2_m128d(r3 + f, r1 + f);   // of records 1, 3
      c[f] = _mm256_unpacklo_pd(even, odd);
      c[f + 1] = _mm256_unpackhi_pd(even, odd);
    }
    return {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]};
  }

  /// The 4 × 4 transposition back to quadruples (8 shuffles), one 256-bit load-add-store each.
  [[gnu::always_inline]] static void addQuadruples(double* __restrict acc, std::size_t lo, const std::int32_t* j,
                                                   int m, Vec ox, Vec oy, Vec oz, Vec od) {
    const __m256d t0 = _mm256_unpacklo_pd(ox, oy), t1 = _mm256_unpackhi_pd(ox, oy);  // lanes 0 2 / 1 3
    const __m256d t2 = _mm256_unpacklo_pd(oz, od), t3 = _mm256_unpackhi_pd(oz, od);
    const __m256d out[4] = {_mm256_permute2f128_pd(t0, t2, 0x20), _mm256_permute2f128_pd(t1, t3, 0x20),
                            _mm256_permute2f128_pd(t0, t2, 0x31), _mm256_permute2f128_pd(t1, t3, 0x31)};
    addQuadruplesEach(acc, lo, j, m, out);
  }
};

/// 4 lanes with AVX2 and FMA only: a mask is a vector whose true lanes are all ones (compares give
/// them, `and` combines them, blendv selects by them); r, 1/r and 1/(r² + η²) are the divider's
/// correctly rounded √ and ÷ (kEstimates false).
struct Lanes4Avx2 : Lanes256 {
  using Mask = __m256d;
  static constexpr bool kEstimates = false;

  /// The first `count` lanes (count in [0, 4]).
  static Mask firstLanes(int count) {
    return _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(count), _mm256_setr_epi64x(0, 1, 2, 3)));
  }
  static Mask all() { return _mm256_castsi256_pd(_mm256_set1_epi64x(-1)); }
  static Mask less(Mask k, Vec a, Vec b) { return _mm256_and_pd(k, _mm256_cmp_pd(a, b, _CMP_LT_OQ)); }
  static Vec maskzMul(Mask k, Vec a, Vec b) { return _mm256_and_pd(k, _mm256_mul_pd(a, b)); }
  static Vec maskMax(Vec src, Mask k, Vec a, Vec b) { return _mm256_blendv_pd(src, _mm256_max_pd(a, b), k); }
  static Vec blend(Mask k, Vec a, Vec b) { return _mm256_blendv_pd(a, b, k); }  // b where k, else a
  /// The lanes' indices; lanes past a list's end read the next list's entries or the padding
  /// (valid particles: NeighbourList::kListPadding), which the masked gather does not follow.
  static Index indices(Mask, const std::int32_t* j) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(j));
  }
  static Vec gather(Mask k, Index j, const double* base) {
    return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, j, k, 8);
  }
};

#ifdef RUPTURE_SPH_AVX512

/// The mask of a block's first `count` lanes (count in [0, 8]): its entries before the list's end.
inline __mmask8 firstLanes(int count) { return static_cast<__mmask8>((1u << count) - 1u); }

/// 8 lanes in one 512-bit register.
struct Lanes8 : LaneArithmetic<8> {
  static constexpr int kWidth = 8;
  using Index = __m256i;
  using Mask = __mmask8;
  static constexpr bool kEstimates = true;

  static Mask firstLanes(int count) { return sph::firstLanes(count); }
  static Mask all() { return 0xFF; }
  static Vec min(Vec a, Vec b) { return _mm512_min_pd(a, b); }
  static Vec max(Vec a, Vec b) { return _mm512_max_pd(a, b); }
  static Vec abs(Vec a) { return _mm512_abs_pd(a); }
  static Vec fmadd(Vec a, Vec b, Vec c) { return _mm512_fmadd_pd(a, b, c); }   // a b + c
  static Vec fmsub(Vec a, Vec b, Vec c) { return _mm512_fmsub_pd(a, b, c); }   // a b − c
  static Vec fnmadd(Vec a, Vec b, Vec c) { return _mm512_fnmadd_pd(a, b, c); } // c − a b
  static Vec rsqrt14(Vec a) { return _mm512_rsqrt14_pd(a); }
  static Vec rcp14(Vec a) { return _mm512_rcp14_pd(a); }
  static __mmask8 less(__mmask8 k, Vec a, Vec b) { return _mm512_mask_cmp_pd_mask(k, a, b, _CMP_LT_OQ); }
  static Vec maskzMul(__mmask8 k, Vec a, Vec b) { return _mm512_maskz_mul_pd(k, a, b); }
  static Vec maskMax(Vec src, __mmask8 k, Vec a, Vec b) { return _mm512_mask_max_pd(src, k, a, b); }
  static Vec blend(__mmask8 k, Vec a, Vec b) { return _mm512_mask_blend_pd(k, a, b); }
  static Index indices(__mmask8 k, const std::int32_t* j) { return _mm256_maskz_loadu_epi32(k, j); }
  static Vec gather(__mmask8 k, Index j, const double* base) {
    return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), k, j, base, 8);
  }
  /// Σ of the 8 lanes, as ((l0 + l4) + (l2 + l6)) + ((l1 + l5) + (l3 + l7)).
  static double reduceAdd(const Vec* parts) {
    return sumOfHalves(_mm512_castpd512_pd256(parts[0]), _mm512_extractf64x4_pd(parts[0], 1));
  }
  static double reduceMax(Vec a) { return _mm512_reduce_max_pd(a); }

  /// The fluid records T::x … of rec[j[0..7]] (64 bytes each, 64-byte aligned) as columns: each
  /// record loaded whole and the 8 × 8 block transposed (24 shuffles: cheaper than 8 gathers).
  template <class Record>
  [[gnu::always_inline]] static Columns columns(const Record* __restrict rec, const std::int32_t* j) {
    // Transposition indices (permutex2var: 0–7 the first operand, 8–15 the second).
    const __m512i lowPairs = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13);
    const __m512i highPairs = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    __m512d r[8];  // rows: the 8 records [x y z p/ρ² vx vy vz 1/ρ]
    for (int l = 0; l < 8; ++l) r[l] = _mm512_load_pd(&rec[j[l]].x);
    __m512d t[8];
    for (int l = 0; l < 4; ++l) {
      t[2 * l] = _mm512_unpacklo_pd(r[2 * l], r[2 * l + 1]);      // x z vx vz of rows 2l, 2l+1
      t[2 * l + 1] = _mm512_unpackhi_pd(r[2 * l], r[2 * l + 1]);  // y p vy 1/ρ
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

  /// acc[4 j[l] …] += (ox, oy, oz, od) of lane l, for the first m lanes: the 4 columns transposed
  /// back into one quadruple per lane (12 shuffles), one 256-bit load-add-store each.
  [[gnu::always_inline]] static void addQuadruples(double* __restrict acc, std::size_t lo, const std::int32_t* j,
                                                   int m, Vec ox, Vec oy, Vec oz, Vec od) {
    const __m512i quadLow = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11);
    const __m512i quadHigh = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
    const __m512d q0 = _mm512_unpacklo_pd(ox, oy), q1 = _mm512_unpackhi_pd(ox, oy);  // lanes 0 2 4 6 / 1 3 5 7
    const __m512d q2 = _mm512_unpacklo_pd(oz, od), q3 = _mm512_unpackhi_pd(oz, od);
    const __m512d v02 = _mm512_permutex2var_pd(q0, quadLow, q2), v46 = _mm512_permutex2var_pd(q0, quadHigh, q2);
    const __m512d v13 = _mm512_permutex2var_pd(q1, quadLow, q3), v57 = _mm512_permutex2var_pd(q1, quadHigh, q3);
    const __m256d out[8] = {_mm512_castpd512_pd256(v02), _mm512_castpd512_pd256(v13),
                            _mm512_extractf64x4_pd(v02, 1), _mm512_extractf64x4_pd(v13, 1),
                            _mm512_castpd512_pd256(v46), _mm512_castpd512_pd256(v57),
                            _mm512_extractf64x4_pd(v46, 1), _mm512_extractf64x4_pd(v57, 1)};
    addQuadruplesEach(acc, lo, j, m, out);
  }

};

/// 4 lanes in one 256-bit register with AVX-512VL's masks and 14-bit estimates.
struct Lanes4 : Lanes256 {
  using Mask = __mmask8;
  static constexpr bool kEstimates = true;

  static Mask firstLanes(int count) { return sph::firstLanes(count); }
  static Mask all() { return 0xFF; }
  static Vec rsqrt14(Vec a) { return _mm256_rsqrt14_pd(a); }
  static Vec rcp14(Vec a) { return _mm256_rcp14_pd(a); }
  static __mmask8 less(__mmask8 k, Vec a, Vec b) { return _mm256_mask_cmp_pd_mask(k, a, b, _CMP_LT_OQ); }
  static Vec maskzMul(__mmask8 k, Vec a, Vec b) { return _mm256_maskz_mul_pd(k, a, b); }
  static Vec maskMax(Vec src, __mmask8 k, Vec a, Vec b) { return _mm256_mask_max_pd(src, k, a, b); }
  static Vec blend(__mmask8 k, Vec a, Vec b) { return _mm256_mask_blend_pd(k, a, b); }
  static Index indices(__mmask8 k, const std::int32_t* j) { return _mm_maskz_loadu_epi32(k, j); }
  static Vec gather(__mmask8 k, Index j, const double* base) {
    return _mm256_mmask_i32gather_pd(_mm256_setzero_pd(), k, j, base, 8);
  }
};

#endif  // RUPTURE_SPH_AVX512

/// √x and 1/√x (x > 0). With the estimates (AVX-512): from the 14-bit estimate y of 1/√x and one
/// correction of fourth order: with e = 1 − x y² (|e| < 2⁻¹³), 1/√x = y (1 − e)^(−½) = y (1 + e/2 +
/// 3e²/8 + 5e³/16 + O(e⁴)), so each is within an ulp or two of double precision (e⁴ ≈ 2⁻⁵²), as two
/// Newton steps would be, in a shorter chain. √x = x y (1 + …) is fused the same way rather than
/// taken as x times 1/√x, which would add a multiplication to the chain that waits on it (the pair
/// loop's r). Without them (AVX2): √x correctly rounded and 1/√x as 1 ÷ √x. A caller that reads one
/// of the two pays for that one only (GCC drops the other).
template <class L>
struct RootAndInverse {
  typename L::Vec root, inverse;
};
template <class L>
[[gnu::always_inline]] inline RootAndInverse<L> rootAndInverse(typename L::Vec x) {
  if constexpr (L::kEstimates) {
    const auto y = L::rsqrt14(x);
    const auto xy = L::mul(x, y);
    const auto e = L::fnmadd(xy, y, L::set1(1.0));
    const auto series = L::fmadd(L::fmadd(L::set1(5.0 / 16.0), e, L::set1(3.0 / 8.0)), e, L::set1(0.5));
    return {L::fmadd(L::mul(xy, e), series, xy), L::fmadd(L::mul(y, e), series, y)};
  } else {
    const auto root = _mm256_sqrt_pd(x);
    return {root, _mm256_div_pd(L::set1(1.0), root)};
  }
}

/// 1/x (x > 0). With the estimates: from the 14-bit estimate y, with e = 1 − x y, 1/x = y/(1 − e) =
/// y (1 + e)(1 + e²) + O(e⁴): double precision to an ulp or two, as two Newton steps, in a shorter
/// chain. Without them: the division.
template <class L>
[[gnu::always_inline]] inline typename L::Vec inverse(typename L::Vec x) {
  if constexpr (L::kEstimates) {
    const auto y = L::rcp14(x);
    const auto e = L::fnmadd(x, y, L::set1(1.0));
    const auto first = L::fmadd(y, e, y);
    return L::fmadd(first, L::mul(e, e), first);
  } else {
    return _mm256_div_pd(L::set1(1.0), x);
  }
}

#endif  // RUPTURE_SPH_AVX2

}  // namespace rupture::sph
