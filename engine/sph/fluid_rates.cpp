#include "sph/fluid_rates.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace rupture::sph {

namespace {

/// Sums of one particle over a run of its neighbours.
struct Sums {
  double ax = 0, ay = 0, az = 0, drho = 0, diffusion = 0, maxMu = 0;
};

/// The pair loop of particle i over neighbours list[begin, end). Diffuse: add the δ-SPH sum.
/// Plain arrays and selects only, so GCC vectorises it (gathers of the neighbours' fields).
template <bool Diffuse, bool UniformMass>
[[gnu::always_inline]] inline void gather(const FluidParticles& p, std::size_t i, const std::int32_t* list, int begin,
                                          int end, const CubicSplineKernel& kernel, double alphaC0, double beta,
                                          const double* hydrostatic, bool is3d, double uniformMass, Sums& s) {
  const double* __restrict x = p.x.data();
  const double* __restrict y = p.y.data();
  const double* __restrict z = p.z.data();
  const double* __restrict vx = p.vxEst.data();
  const double* __restrict vy = p.vyEst.data();
  const double* __restrict vz = p.vzEst.data();
  const double* __restrict rho = p.rhoEst.data();
  const double* __restrict P = p.pressureOverRho2.data();
  const double* __restrict m = p.mass.data();
  const double* __restrict invRho = p.inverseRho.data();
  const double xi = x[i], yi = y[i], zi = is3d ? z[i] : 0.0;
  const double vxi = vx[i], vyi = vy[i], vzi = vz[i], rhoi = rho[i], Pi = P[i], invRhoI = invRho[i];
  const double h = kernel.h(), eta2 = 0.01 * h * h, support2 = 4.0 * h * h;
  const double kx = hydrostatic[0], ky = hydrostatic[1], kz = hydrostatic[2];
  double sax = 0, say = 0, saz = 0, sdrho = 0, sdiff = 0, smu = 0;
#pragma omp simd reduction(+ : sax, say, saz, sdrho, sdiff) reduction(max : smu)
  for (int n = begin; n < end; ++n) {
    const std::int32_t j = list[n];
    const double dx = xi - x[j], dy = yi - y[j], dz = is3d ? zi - z[j] : 0.0;
    const double r2 = dx * dx + dy * dy + dz * dz;
    const double inverseR = 1.0 / std::sqrt(r2 > 1e-300 ? r2 : 1e-300);
    const double F = kernel.gradientFactor(r2 * inverseR, inverseR);  // 0 beyond the support (skin pairs)
    const double dvx = vxi - vx[j], dvy = vyi - vy[j], dvz = vzi - vz[j];
    const double vr = dvx * dx + dvy * dy + dvz * dz;
    const double mu = h * vr / (r2 + eta2);
    const double rhoj = rho[j];
    // 1/ρ̄ as the mean of 1/ρ: equal to 2/(ρ_a + ρ_b) to O((Δρ/ρ)²), 1e-4 here, without a division.
    const double viscous = vr < 0.0 ? (-alphaC0 * mu + beta * mu * mu) * 0.5 * (invRhoI + invRho[j]) : 0.0;
    const double mj = UniformMass ? uniformMass : m[j];
    const double c = mj * (Pi + P[j] + viscous) * F;
    sax -= c * dx;
    say -= c * dy;
    saz -= c * dz;
    sdrho += mj * F * vr;
    if constexpr (Diffuse) sdiff += ((rhoi - rhoj) - (kx * dx + ky * dy + kz * dz)) * F * mj * invRho[j];
    const double amu = r2 < support2 ? std::fabs(mu) : 0.0;
    smu = smu > amu ? smu : amu;
  }
  s.ax += sax; s.ay += say; s.az += saz; s.drho += sdrho; s.diffusion += sdiff;
  s.maxMu = std::max(s.maxMu, smu);
}

}  // namespace

RateExtremes computeRates(FluidParticles& p, const NeighbourList& list, const FluidModel& model) {
  const std::size_t n = p.size();
  const EquationOfState eos = model.eos;
  const CubicSplineKernel kernel = model.kernel();
  const bool is3d = model.dimension == 3;
  const bool diffuse = model.diffusion != DiffusionModel::Off && model.delta > 0;
  // Fourtakas: ρ_a − ρ_b minus its hydrostatic part ρ0 g·x_ab/c0² (acoustic linearisation).
  double hydrostatic[3] = {0, 0, 0};
  if (model.diffusion == DiffusionModel::Fourtakas)
    for (int a = 0; a < 3; ++a) hydrostatic[a] = eos.referenceDensity * model.gravity[a] / (eos.soundSpeed * eos.soundSpeed);
  const double alphaC0 = model.alpha * eos.soundSpeed;
  const double diffusionScale = 2.0 * model.delta * kernel.h() * eos.soundSpeed;

  // Fluid pressures from the equation of state; then the boundary particles' pressures extrapolated
  // from the fluid around them (Adami et al. 2012, eq. 27), their density its EOS inverse.
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t k = 0; k < n; ++k)
    if (p.body[k] == kFluid) p.pressure[k] = eos.pressure(p.rhoEst[k]);
  const double gx = model.gravity[0], gy = model.gravity[1], gz = model.gravity[2];
#pragma omp parallel for schedule(dynamic, 256) if (worthParallel(n))
  for (std::size_t w = 0; w < n; ++w) {
    if (p.body[w] == kFluid) continue;
    const std::int32_t* nb = list.neighbours(w);
    double sumW = 0, sumPW = 0, sumRhoRW = 0;
    for (int k = 0; k < list.count(w); ++k) {
      const std::int32_t f = nb[k];
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
#pragma omp parallel for schedule(static) if (worthParallel(n))
  for (std::size_t k = 0; k < n; ++k) {
    p.inverseRho[k] = 1.0 / p.rhoEst[k];
    p.pressureOverRho2[k] = p.pressure[k] * p.inverseRho[k] * p.inverseRho[k];
  }

  // Equal masses (every lattice-built set): one gather fewer per pair.
  const double uniformMass = n > 0 ? p.mass[0] : 0.0;
  const bool uniform = std::all_of(p.mass.begin(), p.mass.end(), [&](double m) { return m == uniformMass; });
  double maxMu = 0, maxAcc2 = 0, maxRho = 0;
  auto pairLoop = [&]<bool Uniform>() {
#pragma omp parallel for schedule(dynamic, 256) reduction(max : maxMu, maxAcc2, maxRho) if (worthParallel(n))
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t* nb = list.neighbours(i);
    const int nf = list.fluidCount(i), total = list.count(i);
    Sums s;
    if (p.body[i] == kFluid) {
      if (diffuse) gather<true, Uniform>(p, i, nb, 0, nf, kernel, alphaC0, model.beta, hydrostatic, is3d, uniformMass, s);
      else gather<false, Uniform>(p, i, nb, 0, nf, kernel, alphaC0, model.beta, hydrostatic, is3d, uniformMass, s);
      gather<false, Uniform>(p, i, nb, nf, total, kernel, alphaC0, model.beta, hydrostatic, is3d, uniformMass, s);
      const double gx = s.ax + model.gravity[0], gy = s.ay + model.gravity[1], gz = s.az + model.gravity[2];
      maxAcc2 = std::max(maxAcc2, gx * gx + gy * gy + gz * gz);
      maxRho = std::max(maxRho, p.rhoEst[i]);
    } else {
      gather<false, Uniform>(p, i, nb, 0, total, kernel, alphaC0, model.beta, hydrostatic, is3d, uniformMass, s);
    }
    maxMu = std::max(maxMu, s.maxMu);
    p.ax[i] = s.ax;
    p.ay[i] = s.ay;
    p.az[i] = s.az;
    p.drho[i] = s.drho + diffusionScale * s.diffusion;
  }
  };
  if (uniform) pairLoop.template operator()<true>();
  else pairLoop.template operator()<false>();
  return {maxMu, std::sqrt(maxAcc2), maxRho};
}

}  // namespace rupture::sph
