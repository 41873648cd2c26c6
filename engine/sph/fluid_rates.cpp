#include "sph/fluid_rates.hpp"

#include <algorithm>
#include <cmath>

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

}  // namespace

RateExtremes computeRates(FluidParticles& p, const NeighbourList& list, const FluidModel& model,
                          RateWorkspace& ws) {
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

  // Fluid pressures from the equation of state; then the boundary particles' pressures extrapolated
  // from the fluid around them (Adami et al. 2012, eq. 27), their density its EOS inverse.
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t a = 0; a < n; ++a)
    if (p.body[a] == kFluid) p.pressure[a] = eos.pressure(p.rhoEst[a]);
  const double gx = model.gravity[0], gy = model.gravity[1], gz = model.gravity[2];
#pragma omp parallel for schedule(dynamic, 256) if (worthParallel(n))
  for (std::size_t w = 0; w < n; ++w) {
    if (p.body[w] == kFluid) continue;
    const std::int32_t* nb = list.neighbours(w);
    double sumW = 0, sumPW = 0, sumRhoRW = 0;
    for (int m = 0; m < list.count(w); ++m) {
      const std::int32_t f = nb[m];
      const double dx = p.x[w] - p.x[f], dy = p.y[w] - p.y[f], dz = is3d ? p.z[w] - p.z[f] : 0.0;
      const double W = kernel.value(std::sqrt(dx * dx + dy * dy + dz * dz));
      sumW += W;
      sumPW += p.pressure[f] * W;
      sumRhoRW += p.rhoEst[f] * (gx * dx + gy * dy + gz * dz) * W;  // (g − a_w)·Σ ρ_f r_wf W, a_w neglected
    }
    // A wall holds no tension: fluid leaving it must not be pulled back (as DualSPHysics' ρ_w >= ρ0).
    const double pw = sumW > 0 ? std::max(0.0, (sumPW + sumRhoRW) / sumW) : 0.0;
    p.pressure[w] = pw;
    p.rhoEst[w] = pw > 0 ? eos.density(pw) : eos.referenceDensity;
  }
  // What the pair loop reads of a particle, packed into one cache line.
  ws.packed.resize(n);
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t a = 0; a < n; ++a) {
    p.inverseRho[a] = 1.0 / p.rhoEst[a];
    p.pressureOverRho2[a] = p.pressure[a] * p.inverseRho[a] * p.inverseRho[a];
    ws.packed[a] = {p.x[a], p.y[a], is3d ? p.z[a] : 0.0, p.pressureOverRho2[a],
                    p.vxEst[a], p.vyEst[a], is3d ? p.vzEst[a] : 0.0, p.inverseRho[a]};
  }

  // Equal masses (every lattice-built set): one load fewer per pair.
  k.uniformMass = n > 0 ? p.mass[0] : 0.0;
  const bool uniform = std::all_of(p.mass.begin(), p.mass.end(), [&](double m) { return m == k.uniformMass; });

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
      std::fill(acc, acc + 4 * ch.touched(), 0.0);
      double mu = 0;
      for (std::size_t i = ch.begin; i < ch.end; ++i) {
        if (p.body[i] != kFluid) continue;
        const std::int32_t* nb = list.neighbours(i);
        const int nf = list.fluidCount(i), total = list.count(i);
        double own[4] = {0, 0, 0, 0};
        if (diffuse) pairsOf<true, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, ch.lo, k, own, mu);
        else pairsOf<false, Uniform>(i, nb, 0, nf, pk, rho, mass, acc, ch.lo, k, own, mu);
        pairsOf<false, Uniform>(i, nb, nf, total, pk, rho, mass, acc, ch.lo, k, own, mu);
        double* ai = acc + 4 * (i - ch.lo);
        for (int a = 0; a < 4; ++a) ai[a] += own[a];
      }
      maxMu = std::max(maxMu, mu);
    }
  };
  if (uniform) chunkLoop.template operator()<true>();
  else chunkLoop.template operator()<false>();

  // The chunks' buffers added in chunk order: the same sums for any thread count.
  const double massScale = uniform ? k.uniformMass : 1.0;
  double maxAcc2 = 0, maxRho = 0;
#pragma omp parallel for schedule(static) reduction(max : maxAcc2, maxRho) if (worthParallel(n))
  for (std::size_t a = 0; a < n; ++a) {
    double s[4] = {0, 0, 0, 0};
    for (std::size_t c = 0; c < chunks.size(); ++c) {
      const NeighbourList::Chunk& ch = chunks[c];
      if (ch.touched() == 0 || a < ch.lo || a > ch.hi) continue;
      const double* v = ws.sums.data() + offset[c] + 4 * (a - ch.lo);
      for (int m = 0; m < 4; ++m) s[m] += v[m];
    }
    for (int m = 0; m < 4; ++m) s[m] *= massScale;
    p.ax[a] = s[0];
    p.ay[a] = s[1];
    p.az[a] = s[2];
    if (p.body[a] == kFluid) {
      p.drho[a] = s[3];
      const double fx = s[0] + gx, fy = s[1] + gy, fz = s[2] + gz;
      maxAcc2 = std::max(maxAcc2, fx * fx + fy * fy + fz * fz);
      maxRho = std::max(maxRho, p.rhoEst[a]);
    } else {
      p.drho[a] = 0;  // boundary densities are extrapolated, not integrated
    }
  }
  return {maxMu, std::sqrt(maxAcc2), maxRho};
}

}  // namespace rupture::sph
