#pragma once
// Isotropic hardening laws σ_y(p) of von Mises plasticity, p the accumulated (equivalent) plastic
// strain. Two forms:
//   linear:        σ_y(p) = σ_y0 + H p
//   johnson_cook:  σ_y(p) = A + B p^n   (Johnson & Cook 1983 without the rate and temperature
//                  factors; also called Ludwik's law). AU4G 2024-T351 is rate-insensitive in the
//                  tests of Caleyron et al. 2013 (§4.1), and the published 2024-T351 fits are of this form.
// Units: stresses in Pa, p dimensionless.
#include <algorithm>
#include <cmath>
#include <string>

namespace rupture {

enum class HardeningKind { linear, johnsonCook };

struct IsotropicHardening {
  HardeningKind kind = HardeningKind::johnsonCook;
  double initialYieldStress = 265.0e6;  ///< σ_y0 or A (Pa)
  double modulus = 426.0e6;             ///< H (linear) or B (johnson_cook) (Pa)
  double exponent = 0.34;               ///< n (johnson_cook only), in (0, 1]

  double yieldStress(double p) const {
    if (kind == HardeningKind::linear) return initialYieldStress + modulus * p;
    return initialYieldStress + (p > 0.0 ? modulus * std::pow(p, exponent) : 0.0);
  }

  /// dσ_y/dp. For n < 1 the power law has an infinite slope at p = 0; the slope is evaluated at
  /// p >= kMinSlopeStrain so that the return-mapping Newton step stays finite (the bracketed
  /// solver does not rely on it for convergence).
  double slope(double p) const {
    if (kind == HardeningKind::linear) return modulus;
    const double q = std::max(p, kMinSlopeStrain);
    return modulus * exponent * std::pow(q, exponent - 1.0);
  }

  static constexpr double kMinSlopeStrain = 1.0e-6;
};

/// Throws SpecError naming `<prefix>.<field>` for a value outside its range.
void validateHardening(const IsotropicHardening& h, const std::string& prefix);

/// "linear" or "johnson_cook"; throws SpecError(field) for any other name.
HardeningKind hardeningKindFromName(const std::string& name, const std::string& field);
const char* hardeningKindName(HardeningKind kind);

}  // namespace rupture
