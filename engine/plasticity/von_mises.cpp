#include "plasticity/von_mises.hpp"

#include <cmath>

#include "core/format_number.hpp"
#include "rupture/spec_error.hpp"

namespace rupture {
namespace {

/// Root of a strictly decreasing residual r on [0, hi] with r(0) > 0 and r(hi) < 0: Newton steps,
/// falling back to bisection when a step leaves the bracket. Converges to round-off.
template <class Residual>
double decreasingRoot(Residual&& residual, double hi) {
  double lo = 0.0, x = 0.0;
  for (int it = 0; it < 200; ++it) {
    double dr = 0.0;
    const double r = residual(x, dr);
    if (r > 0.0) lo = x; else hi = x;
    if (r == 0.0 || hi - lo <= 1e-15 * hi) return x;
    double next = (dr < 0.0) ? x - r / dr : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-15 * std::max(std::abs(x), 1e-300)) return next;
    x = next;
  }
  return x;
}

}  // namespace

void validateElasticPlastic(const ElasticPlasticMaterial& m, const std::string& prefix) {
  if (!(std::isfinite(m.youngModulus) && m.youngModulus > 0.0))
    throw SpecError(prefix + ".young_modulus", formatNumber(m.youngModulus), "a modulus > 0 (Pa)");
  if (!(m.poissonRatio > -1.0 && m.poissonRatio < 0.5))
    throw SpecError(prefix + ".poisson_ratio", formatNumber(m.poissonRatio), "a number in (-1, 0.5)");
  validateHardening(m.hardening, prefix);
}

double vonMisesStress(const SymTensor3& s) {
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

double vonMisesStress(const PlaneTensor& s) { return vonMisesStress(s, {0.0, 0.0}); }

double vonMisesStress(const PlaneTensor& s, const TransverseShear& q) {
  return std::sqrt(std::max(0.0, s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3.0 * (s[2] * s[2] + q[0] * q[0] + q[1] * q[1])));
}

double hydrostaticStress(const SymTensor3& s) { return (s[0] + s[1] + s[2]) / 3.0; }

ReturnMapping radialReturn3D(const ElasticPlasticMaterial& m, SymTensor3& stress, double p) {
  const double sigmaEqTrial = vonMisesStress(stress);
  const IsotropicHardening& h = m.hardening;
  if (sigmaEqTrial <= h.yieldStress(p)) return {};
  const double G = m.shearModulus();
  // r(Δp) = σ_eq^tr − 3G Δp − σ_y(p + Δp): decreasing, r(σ_eq^tr / 3G) = −σ_y < 0.
  const double dp = decreasingRoot(
      [&](double x, double& dr) {
        dr = -3.0 * G - h.slope(p + x);
        return sigmaEqTrial - 3.0 * G * x - h.yieldStress(p + x);
      },
      sigmaEqTrial / (3.0 * G));
  // Radial return: the deviator shrinks by (1 − 3G Δp / σ_eq^tr), the mean stress is kept.
  const double mean = hydrostaticStress(stress);
  const double scale = 1.0 - 3.0 * G * dp / sigmaEqTrial;
  for (int k = 0; k < 3; ++k) stress[k] = mean + scale * (stress[k] - mean);
  for (int k = 3; k < 6; ++k) stress[k] *= scale;
  return {dp, 1.5 * dp / (sigmaEqTrial - 3.0 * G * dp), true};
}

PlaneTensor planeStressElastic(const ElasticPlasticMaterial& m, const PlaneTensor& e) {
  const double E = m.youngModulus, nu = m.poissonRatio, c = E / (1.0 - nu * nu);
  return {c * (e[0] + nu * e[1]), c * (e[1] + nu * e[0]), 2.0 * m.shearModulus() * e[2]};
}

ReturnMapping shellReturn(const ElasticPlasticMaterial& m, PlaneTensor& stress, TransverseShear& shear, double p) {
  const IsotropicHardening& h = m.hardening;
  // σ_y(p) >= σ_y0 (the hardening modulus is >= 0): below σ_y0 the layer is elastic without the
  // power law's std::pow, the same decision as against σ_y(p).
  const double trialStress = vonMisesStress(stress, shear);
  if (trialStress <= h.initialYieldStress || trialStress <= h.yieldStress(p)) return {};
  const double E = m.youngModulus, nu = m.poissonRatio, G = m.shearModulus();
  // Components in the common eigenbasis of C and P (de Souza Neto et al. 2008, eq. 9.43):
  // a1 = (σ11+σ22)/√2 (P: 1/3, C: E/(1−ν)), a2 = (σ22−σ11)/√2 (P: 1, C: 2G), σ12 (P: 2, C: 2G);
  // the transverse shears σ13, σ23 are shears like σ12 (P: 2, C: 2G): they scale with it.
  const double a1 = (stress[0] + stress[1]) / std::sqrt(2.0);
  const double a2 = (stress[1] - stress[0]) / std::sqrt(2.0);
  const double a3 = stress[2];
  const double shears = a3 * a3 + shear[0] * shear[0] + shear[1] * shear[1];
  const double c1 = E / (3.0 * (1.0 - nu)), c2 = 2.0 * G;
  // ξ(Δγ) = σᵀPσ = 2 J2 with σ(Δγ) = (I + Δγ C P)⁻¹ σ^tr.
  auto xi = [&](double g, double& dxi) {
    const double d1 = 1.0 + c1 * g, d2 = 1.0 + c2 * g;
    const double t1 = a1 * a1 / 3.0, t2 = a2 * a2 + 2.0 * shears;
    dxi = -2.0 * c1 * t1 / (d1 * d1 * d1) - 2.0 * c2 * t2 / (d2 * d2 * d2);
    return t1 / (d1 * d1) + t2 / (d2 * d2);
  };
  // r(Δγ) = σ_eq(Δγ) − σ_y(p + Δp(Δγ)), σ_eq = √(3ξ/2), Δp = Δγ √(2ξ/3): strictly decreasing.
  auto residual = [&](double g, double& dr) {
    double dxi = 0.0;
    const double x = std::max(xi(g, dxi), 1e-300);
    const double sigmaEq = std::sqrt(1.5 * x), root = std::sqrt(2.0 * x / 3.0);
    const double dp = g * root;
    const double dSigmaEq = 0.75 * dxi / sigmaEq;
    const double dDp = root + g * (dxi / 3.0) / root;
    dr = dSigmaEq - h.slope(p + dp) * dDp;
    return sigmaEq - h.yieldStress(p + dp);
  };
  // Bracket: double the upper end until the residual is negative.
  double hi = 1.0 / c2, dr = 0.0;
  while (residual(hi, dr) > 0.0) hi *= 2.0;
  const double g = decreasingRoot(residual, hi);
  const double d1 = 1.0 + c1 * g, d2 = 1.0 + c2 * g;
  const double b1 = a1 / d1, b2 = a2 / d2;
  stress = {(b1 - b2) / std::sqrt(2.0), (b1 + b2) / std::sqrt(2.0), a3 / d2};
  shear = {shear[0] / d2, shear[1] / d2};
  double dxi = 0.0;
  const double dp = g * std::sqrt(2.0 * xi(g, dxi) / 3.0);
  return {dp, g, true};
}

ReturnMapping planeStressReturn(const ElasticPlasticMaterial& m, PlaneTensor& stress, double p) {
  TransverseShear none{0.0, 0.0};
  return shellReturn(m, stress, none, p);
}

ReturnMapping shellPointUpdate(const ElasticPlasticMaterial& m, const PlaneTensor& totalStrain,
                               const TransverseShear& transverseStrain, PlaneTensor& plasticStrainTensor,
                               TransverseShear& plasticShear, double& plasticStrain, PlaneTensor& stress,
                               TransverseShear& shear) {
  const double G = m.shearModulus();
  stress = planeStressElastic(m, {totalStrain[0] - plasticStrainTensor[0], totalStrain[1] - plasticStrainTensor[1],
                                  totalStrain[2] - plasticStrainTensor[2]});
  shear = {2.0 * G * (transverseStrain[0] - plasticShear[0]), 2.0 * G * (transverseStrain[1] - plasticShear[1])};
  const ReturnMapping r = shellReturn(m, stress, shear, plasticStrain);
  if (r.plastic) {
    // Flow ε^p += Δγ P σ (tensor shears: Δε^p_α3 = Δγ σ_α3, as Δε^p_12 = Δγ σ12).
    const double g = r.plasticMultiplier;
    plasticStrainTensor[0] += g * (2.0 * stress[0] - stress[1]) / 3.0;
    plasticStrainTensor[1] += g * (2.0 * stress[1] - stress[0]) / 3.0;
    plasticStrainTensor[2] += g * stress[2];
    plasticShear[0] += g * shear[0];
    plasticShear[1] += g * shear[1];
    plasticStrain += r.plasticStrainIncrement;
  }
  return r;
}

ReturnMapping planeStressPointUpdate(const ElasticPlasticMaterial& m, const PlaneTensor& totalStrain,
                                     PlaneTensor& plasticStrainTensor, double& plasticStrain,
                                     PlaneTensor& stress) {
  TransverseShear plasticShear{0.0, 0.0}, shear{0.0, 0.0};
  return shellPointUpdate(m, totalStrain, {0.0, 0.0}, plasticStrainTensor, plasticShear, plasticStrain, stress, shear);
}

void updateStress3D(const ElasticPlasticMaterial& m, std::span<const SymTensor3> strainIncrement,
                    std::span<SymTensor3> stress, std::span<double> plasticStrain) {
  const double K = m.bulkModulus(), G = m.shearModulus();
  const std::size_t n = stress.size();
  for (std::size_t i = 0; i < n; ++i) {
    const SymTensor3& de = strainIncrement[i];
    const double dv = de[0] + de[1] + de[2];
    SymTensor3& s = stress[i];
    for (int k = 0; k < 3; ++k) s[k] += K * dv + 2.0 * G * (de[k] - dv / 3.0);
    for (int k = 3; k < 6; ++k) s[k] += 2.0 * G * de[k];
    plasticStrain[i] += radialReturn3D(m, s, plasticStrain[i]).plasticStrainIncrement;
  }
}

void updateStressPlaneStress(const ElasticPlasticMaterial& m, std::span<const PlaneTensor> totalStrain,
                             std::span<PlaneTensor> plasticStrainTensor,
                             std::span<double> plasticStrain, std::span<PlaneTensor> stress) {
  for (std::size_t i = 0; i < stress.size(); ++i)
    planeStressPointUpdate(m, totalStrain[i], plasticStrainTensor[i], plasticStrain[i], stress[i]);
}

}  // namespace rupture
