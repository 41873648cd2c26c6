#include "sph/fluid_rates.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/parallel.hpp"
#include "sph/simd_lanes.hpp"

namespace rupture::sph {

namespace {

using Packed = RateWorkspace::Packed;

/// Constants of the pair loop.
struct PairConstants {
  double h, twoH, eta2, support2, alphaC0, beta, kx, ky, kz, diffusionScale, uniformMass;
  // The cubic spline's F = (dW/dr)/r, kF = 0.75 a_D/h³: kF (3r − 4h) for r < h (the 1/r cancels),
  // −kF (2h − r)²/r for h <= r < 2h. The vector loop computes both pieces and picks one: the near
  // one is a single operation after r, the far one three, a shorter chain than one expression
  // for both (4 max(h − r, 0)² − (2h − r)²)/r.
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
      const double t = k.twoH - r;
      const double F = !inside ? 0.0 : r < k.h ? k.kF * (3.0 * r - 4.0 * k.h) : -k.kF * t * t / r;
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

#ifdef RUPTURE_SPH_AVX2
/// How far ahead in the neighbour list the vector loop prefetches (entries).
constexpr int kPrefetch = 16;
static_assert(kPrefetch + 8 <= NeighbourList::kListPadding, "the loop reads up to kPrefetch + 8 entries past a list");

/// pairsOf in vectors of L::kWidth (4 or 8) neighbours, in blocks of 8: the neighbours' 64-byte
/// records are loaded whole and transposed into columns (no gathers), the pair terms computed in
/// vectors (a lane of a partial block or a skin pair gets F = 0), and the results transposed back
/// into (ax, ay, az, dρ/dt) quadruples added to the neighbours' accumulators, one 256-bit
/// load-add-store each. The neighbours of one particle are distinct, so the updates of a block
/// never meet. Lane l of a block sums into lane l of i's sums at either width (simd_lanes.hpp), so
/// the results are bitwise the same for 4 and 8 lanes and for any thread count.
template <class L, bool Diffuse, bool UniformMass>
[[gnu::always_inline]] inline void pairsOfLanes(std::size_t i, const std::int32_t* __restrict list, int begin,
                                                int end, const Packed* __restrict pk, const double* __restrict rho,
                                                const double* __restrict mass, double* __restrict acc, std::size_t lo,
                                                const PairConstants& k, double own[4], double& maxMu) {
  using Vec = typename L::Vec;
  constexpr int kWidth = L::kWidth, kParts = 8 / kWidth;
  const Packed& a = pk[i];
  const Vec ax = L::set1(a.x), ay = L::set1(a.y), az = L::set1(a.z);
  const Vec avx = L::set1(a.vx), avy = L::set1(a.vy), avz = L::set1(a.vz);
  const Vec ap = L::set1(a.pressureOverRho2), air = L::set1(a.inverseRho);
  const Vec support2 = L::set1(k.support2), tiny = L::set1(1e-300);
  const Vec h = L::set1(k.h), twoH = L::set1(k.twoH), minusKF = L::set1(-k.kF);
  const Vec threeKF = L::set1(3.0 * k.kF), fourHKF = L::set1(4.0 * k.h * k.kF);
  const Vec eta2 = L::set1(k.eta2), zero = L::zero();
  const Vec halfBeta = L::set1(k.halfBeta), halfAlphaC0 = L::set1(k.halfAlphaC0);
  const Vec mi = L::set1(UniformMass ? 1.0 : mass[i]);
  Vec sax[kParts], say[kParts], saz[kParts], sdrho[kParts];
  for (int part = 0; part < kParts; ++part) sax[part] = say[part] = saz[part] = sdrho[part] = zero;
  Vec smu = zero;
  for (int n0 = begin; n0 < end; n0 += 8) {
    // Lanes [s, s + kWidth) of the list, summed into part `part` of i's sums. (A loop, not a
    // lambda: GCC reloaded a lambda's captured constants from memory on every block.)
#pragma GCC unroll 2
    for (int part = 0; part < kParts; ++part) {
      const int s = n0 + part * kWidth;
      if (part > 0 && s >= end) break;
      const int m = std::min(kWidth, end - s);
      const typename L::Mask valid = L::firstLanes(m);
      // Lanes past the end read the next list's entries (or the padding): valid particles, their F
      // masked to 0 and their scatter skipped.
      const std::int32_t* jj = list + s;
      // The records and accumulators of the neighbours kPrefetch entries ahead (they may be the next
      // particle's: the lists lie back to back, padded at the end, neighbour_list.hpp): a
      // neighbour's record is mostly in L3 (the cell-ordered sweep reuses it ~3 MB later).
      for (int l = 0; l < kWidth; ++l) {
        const std::int32_t ahead = jj[kPrefetch + l];
        __builtin_prefetch(&pk[ahead], 0, 3);
        __builtin_prefetch(acc + 4 * (static_cast<std::size_t>(ahead) - lo), 1, 3);
      }
      const typename L::Columns b = L::columns(pk, jj);
      const Vec dx = L::sub(ax, b.x), dy = L::sub(ay, b.y), dz = L::sub(az, b.z);
      const Vec r2 = L::fmadd(dz, dz, L::fmadd(dy, dy, L::mul(dx, dx)));
      const typename L::Mask inside = L::less(valid, r2, support2);  // skin pairs: none
      const Vec r2Safe = L::max(r2, tiny);  // two particles at one point: a finite F (and x_ab = 0), not NaN
      const auto [rr, inverseR] = rootAndInverse<L>(r2Safe);
      const Vec near = L::fmsub(threeKF, rr, fourHKF), tt = L::sub(twoH, rr);  // the two pieces (PairConstants)
      const Vec far = L::maskzMul(inside, L::mul(minusKF, tt), L::mul(tt, inverseR));  // 0 for skin pairs
      const Vec F = L::blend(L::less(inside, rr, h), far, near);
      const Vec dvx = L::sub(avx, b.vx), dvy = L::sub(avy, b.vy), dvz = L::sub(avz, b.vz);
      const Vec vr = L::fmadd(dvz, dz, L::fmadd(dvy, dy, L::mul(dvx, dx)));
      const Vec mu = L::mul(L::mul(h, vr), inverse<L>(L::add(r2, eta2)));
      // Π only for approaching pairs (μ < 0), as min(μ, 0); 1/ρ̄ as the mean of 1/ρ (see pairsOf).
      const Vec approach = L::min(mu, zero);
      const Vec viscous =  // two products side by side, then one: a shorter chain after μ
          L::mul(L::mul(approach, L::add(air, b.inverseRho)), L::fmsub(halfBeta, approach, halfAlphaC0));
      const Vec c = L::mul(L::add(L::add(ap, b.pressureOverRho2), viscous), F);
      const Vec fx = L::mul(c, dx), fy = L::mul(c, dy), fz = L::mul(c, dz);
      const Vec continuity = L::mul(F, vr);
      Vec mj = L::set1(1.0);
      typename L::Index idx{};
      if constexpr (!UniformMass || Diffuse) idx = L::indices(valid, jj);  // for the gathers of m_b and ρ_b
      if constexpr (!UniformMass) mj = L::gather(valid, idx, mass);
      sax[part] = L::fnmadd(mj, fx, sax[part]);
      say[part] = L::fnmadd(mj, fy, say[part]);
      saz[part] = L::fnmadd(mj, fz, saz[part]);
      Vec od;
      if constexpr (Diffuse) {
        const Vec rhoj = L::gather(valid, idx, rho);
        const Vec hydrostatic = L::fmadd(L::set1(k.kz), dz, L::fmadd(L::set1(k.ky), dy, L::mul(L::set1(k.kx), dx)));
        const Vec d =
            L::mul(L::mul(L::sub(L::sub(L::set1(rho[i]), rhoj), hydrostatic), F), L::set1(k.diffusionScale));
        sdrho[part] = L::fmadd(mj, L::fmadd(d, b.inverseRho, continuity), sdrho[part]);
        od = L::fnmadd(d, air, continuity);
      } else {
        sdrho[part] = L::fmadd(mj, continuity, sdrho[part]);
        od = continuity;
      }
      smu = L::maskMax(smu, inside, smu, L::abs(mu));
      if constexpr (UniformMass) {
        L::addQuadruples(acc, lo, jj, m, fx, fy, fz, od);
      } else {
        L::addQuadruples(acc, lo, jj, m, L::mul(mi, fx), L::mul(mi, fy), L::mul(mi, fz), L::mul(mi, od));
      }
    }
  }
  own[0] += L::reduceAdd(sax);
  own[1] += L::reduceAdd(say);
  own[2] += L::reduceAdd(saz);
  own[3] += L::reduceAdd(sdrho);
  maxMu = std::max(maxMu, L::reduceMax(smu));
}
#endif

/// The lane type of the portable loops (pairsOf, WallSums::portableSums): every build has them.
struct PortableLanes {};

/// The Shepard sums of a boundary particle at (xw, yw, zw) over its fluid neighbours (Adami et al.
/// 2012, eq. 27): Σ W, Σ p_f W and Σ ρ_f (g·x_wf) W, read from the fluid's records (ρ_f = 1/(1/ρ)_f,
/// p_f = (p/ρ²)_f ρ_f²). Neighbours in the skin (r >= 2h) add nothing.
struct WallSums {
  CubicSplineKernel kernel;
  double gx, gy, gz;

#ifdef RUPTURE_SPH_AVX2
  /// L::kWidth neighbours at a time from their records (L::columns), in blocks of 8 as the pair
  /// loop (the same sums at either width); lanes past the end read the next list's entries or the
  /// padding (valid particles) and are masked out.
  template <class L>
  [[gnu::always_inline]] void laneSums(double xw, double yw, double zw, const std::int32_t* __restrict list, int count,
                                       const Packed* __restrict pk, double& sumW, double& sumPW,
                                       double& sumRhoRW) const {
    using Vec = typename L::Vec;
    constexpr int kWidth = L::kWidth, kParts = 8 / kWidth;
    const Vec vxw = L::set1(xw), vyw = L::set1(yw), vzw = L::set1(zw);
    const Vec invH = L::set1(1.0 / kernel.h()), two = L::set1(2.0), one = L::set1(1.0);
    const Vec tiny = L::set1(1e-300), aD = L::set1(kernel.normalisation());
    const Vec vgx = L::set1(gx), vgy = L::set1(gy), vgz = L::set1(gz);
    Vec sW[kParts], sPW[kParts], sRR[kParts];
    for (int part = 0; part < kParts; ++part) sW[part] = sPW[part] = sRR[part] = L::zero();
    for (int n0 = 0; n0 < count; n0 += 8) {
#pragma GCC unroll 2
      for (int part = 0; part < kParts; ++part) {
        const int s = n0 + part * kWidth;
        if (part > 0 && s >= count) break;
        const typename L::Mask valid = L::firstLanes(std::min(kWidth, count - s));
        // As the pair loop: the records kPrefetch entries ahead, which may be the next wall's (the
        // walls' lists lie back to back too).
        for (int l = 0; l < kWidth; ++l) __builtin_prefetch(&pk[list[s + kPrefetch + l]], 0, 3);
        const typename L::Columns f = L::columns(pk, list + s);
        const Vec dx = L::sub(vxw, f.x), dy = L::sub(vyw, f.y), dz = L::sub(vzw, f.z);
        const Vec r2 = L::max(L::fmadd(dz, dz, L::fmadd(dy, dy, L::mul(dx, dx))), tiny);
        const Vec q = L::mul(rootAndInverse<L>(r2).root, invH);
        const typename L::Mask inside = L::less(valid, q, two);
        // w = 1 − 1.5 q² + 0.75 q³ (q < 1), 0.25 (2 − q)³ (1 <= q < 2).
        const Vec q2 = L::mul(q, q);
        const Vec nearW = L::fmadd(q2, L::fmsub(L::set1(0.75), q, L::set1(1.5)), one);
        const Vec t = L::sub(two, q);
        const Vec farW = L::mul(L::mul(L::set1(0.25), t), L::mul(t, t));
        const typename L::Mask isNear = L::less(L::all(), q, one);
        const Vec W = L::maskzMul(inside, aD, L::blend(isNear, farW, nearW));
        const Vec rho = inverse<L>(f.inverseRho);
        const Vec pressure = L::mul(L::mul(f.pressureOverRho2, rho), rho);
        const Vec gr = L::fmadd(vgz, dz, L::fmadd(vgy, dy, L::mul(vgx, dx)));
        sW[part] = L::add(sW[part], W);
        sPW[part] = L::fmadd(pressure, W, sPW[part]);
        sRR[part] = L::fmadd(L::mul(rho, gr), W, sRR[part]);  // (g − a_w)·Σ ρ_f x_wf W, a_w neglected
      }
    }
    sumW = L::reduceAdd(sW);
    sumPW = L::reduceAdd(sPW);
    sumRhoRW = L::reduceAdd(sRR);
  }
#endif
  /// The portable sums (std::sqrt and division), one neighbour at a time.
  void portableSums(double xw, double yw, double zw, const std::int32_t* __restrict list, int count,
                    const Packed* __restrict pk, double& sumW, double& sumPW, double& sumRhoRW) const {
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
  }

  /// The sums in the lanes L (laneSums), or the portable ones for PortableLanes.
  template <class L>
  [[gnu::always_inline]] void sums(double xw, double yw, double zw, const std::int32_t* __restrict list, int count,
                                   const Packed* __restrict pk, double& sumW, double& sumPW, double& sumRhoRW) const {
#ifdef RUPTURE_SPH_AVX2
    if constexpr (!std::is_same_v<L, PortableLanes>) {
      laneSums<L>(xw, yw, zw, list, count, pk, sumW, sumPW, sumRhoRW);
    } else
#endif
    {
      portableSums(xw, yw, zw, list, count, pk, sumW, sumPW, sumRhoRW);
    }
  }
};

/// The pairs of fluid particle i (its list nb: nf fluid neighbours, then the walls, total in all),
/// in the lanes L, or by pairsOf for PortableLanes. With density diffusion the fluid and the wall
/// neighbours run apart (the δ-SPH term is the fluid's); without it, in the lanes, in one run:
/// fewer partial blocks.
template <class L, bool Uniform>
[[gnu::always_inline]] inline void pairsOfParticle(bool diffuse, std::size_t i, const std::int32_t* __restrict nb, int nf,
                                                   int total, const Packed* __restrict pk, const double* __restrict rho,
                                                   const double* __restrict mass, double* __restrict acc,
                                                   std::size_t lo, const PairConstants& k, double own[4],
                                                   double& maxMu) {
#ifdef RUPTURE_SPH_AVX2
  if constexpr (!std::is_same_v<L, PortableLanes>) {
    if (diffuse) {
      pairsOfLanes<L, true, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, lo, k, own, maxMu);
      pairsOfLanes<L, false, Uniform>(i, nb, nf, total, pk, rho, mass, acc, lo, k, own, maxMu);
    } else {
      pairsOfLanes<L, false, Uniform>(i, nb, 0, total, pk, rho, mass, acc, lo, k, own, maxMu);
    }
  } else
#endif
  {
    if (diffuse) pairsOf<true, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, lo, k, own, maxMu);
    else pairsOf<false, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, lo, k, own, maxMu);
    pairsOf<false, Uniform>(i, nb, nf, total, pk, rho, mass, acc, lo, k, own, maxMu);
  }
}

/// f.operator()<L>() with the lane type of `width` (kPortableLanes, 4 or 8; 0: this processor's,
/// simd_lanes.hpp): Lanes4 or Lanes8 with AVX-512, Lanes4Avx2 for 4 or 8 with AVX2 and FMA only,
/// PortableLanes for kPortableLanes or where the build has neither.
template <class F>
void withLanes(int width, F&& f) {
  const int w = width == 0 ? preferredLaneWidth() : width;
#if defined(RUPTURE_SPH_AVX512)
  if (w == 4) f.template operator()<Lanes4>();
  else if (w == 8) f.template operator()<Lanes8>();
  else f.template operator()<PortableLanes>();
#elif defined(RUPTURE_SPH_AVX2)
  if (w == 4 || w == 8) f.template operator()<Lanes4Avx2>();
  else f.template operator()<PortableLanes>();
#else
  (void)w;
  f.template operator()<PortableLanes>();
#endif
}

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
  //    line: position, p/ρ², velocity estimate, 1/ρ). Boundary particles: the record of a dry wall
  //    (p = 0, ρ = ρ0), replaced in 2. for those with fluid in reach; no branch on the kind, which
  //    alternates along the cell-ordered particles (so every particle costs the same: static).
  //    Equal masses (every lattice-built set) save the pair loop a load per pair; checked here,
  //    over every particle.
  ws.packed.resize(n);
  Packed* packed = ws.packed.data();
  const double rho0 = eos.referenceDensity;
  double minMass = n > 0 ? p.mass[0] : 0.0, maxMass = minMass;
  // In blocks, polling between them: the first pass of a run also faults in the records' pages
  // (150 MB for 2.3 M particles, half a second), which must not delay a cancel.
  constexpr std::size_t kBlock = std::size_t{1} << 18;
  for (std::size_t a0 = 0; a0 < n; a0 += kBlock) {
    if (ws.cancel.requested()) return {};
    const std::size_t a1 = std::min(n, a0 + kBlock);
#pragma omp parallel for schedule(static) reduction(min : minMass) reduction(max : maxMass) if (worthParallel(a1 - a0))
    for (std::size_t a = a0; a < a1; ++a) {
      minMass = std::min(minMass, p.mass[a]);
      maxMass = std::max(maxMass, p.mass[a]);
      const double rho = p.body[a] == kFluid ? p.rhoEst[a] : rho0;
      const double pressure = eos.pressure(rho), inverseRho = 1.0 / rho;  // p(ρ0) = 0 exactly
      p.rhoEst[a] = rho;
      p.pressure[a] = pressure;
      packed[a] = recordOf(p, a, pressure, inverseRho, is3d);
    }
  }
  if (ws.cancel.requested()) return {};
  // 2. Boundary particles with fluid in reach: the pressure extrapolated from the fluid around them
  //    (Adami et al. 2012, eq. 27), their density its EOS inverse, and their record.
  const double gx = model.gravity[0], gy = model.gravity[1], gz = model.gravity[2];
  const WallSums wallSums{kernel, gx, gy, gz};
  const std::vector<NeighbourList::WetBoundary>& wet = list.wetBoundary();
  auto wallPass = [&]<class L>() {
#pragma omp parallel for schedule(dynamic, 256) if (worthParallel(n))
    for (std::size_t q = 0; q < wet.size(); ++q) {
      const NeighbourList::WetBoundary& wall = wet[q];
      Packed& record = packed[wall.particle];  // position and velocity from 1.
      double sumW = 0, sumPW = 0, sumRhoRW = 0;
      wallSums.template sums<L>(record.x, record.y, record.z, wall.neighbours, wall.count, packed, sumW, sumPW, sumRhoRW);
      // A wall holds no tension: fluid leaving it must not be pulled back (as DualSPHysics' ρ_w >= ρ0).
      const double pw = sumW > 0 ? std::max(0.0, (sumPW + sumRhoRW) / sumW) : 0.0;
      if (pw == 0.0) continue;  // the dry record of 1.
      const double rhow = eos.density(pw), inverseRho = 1.0 / rhow;
      p.pressure[wall.particle] = pw;
      p.rhoEst[wall.particle] = rhow;
      record.pressureOverRho2 = pw * inverseRho * inverseRho;
      record.inverseRho = inverseRho;
    }
  };
  withLanes(ws.laneWidth, wallPass);

  if (ws.cancel.requested()) return {};
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
  auto chunkLoop = [&]<class L, bool Uniform>() {
#pragma omp parallel for schedule(dynamic, 1) reduction(max : maxMu) if (chunks.size() > 1)
    for (std::size_t c = 0; c < chunks.size(); ++c) {
      if (ws.cancel.requested()) continue;
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
        pairsOfParticle<L, Uniform>(diffuse, i, nb, nf, total, pk, rho, mass, acc, ch.lo, k, own, mu);
        double* ai = acc + 4 * (i - ch.lo);
        for (int a = 0; a < 4; ++a) ai[a] += own[a];
      }
      maxMu = std::max(maxMu, mu);
    }
  };
  withLanes(ws.laneWidth, [&]<class L>() {
    if (uniform) chunkLoop.template operator()<L, true>();
    else chunkLoop.template operator()<L, false>();
  });

  // Skipped chunks left their buffers unwritten (scratch): nothing below may read them.
  if (ws.cancel.requested()) return {};

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
