#pragma once
// Equations of state of a weakly compressible liquid (docs/references.md#eq-sph):
//   acoustic (Caleyron et al. 2013 eq. 3):  p = c0² (ρ − ρ0)
//   Tait (Monaghan 1994; Batchelor):         p = B [(ρ/ρ0)^γ − 1],  B = ρ0 c0²/γ,  γ = 7
// Both have sound speed c0 at ρ0. Pressures in Pa, densities in kg/m³, speeds in m/s.
#include <cmath>
#include <string>

namespace rupture::sph {

enum class EosKind { Tait, Acoustic };

inline std::string toString(EosKind k) { return k == EosKind::Tait ? "tait" : "acoustic"; }

struct EquationOfState {
  EosKind kind = EosKind::Tait;
  double referenceDensity = 1000.0;  ///< ρ0 (kg/m³)
  double soundSpeed = 1450.0;        ///< c0 (m/s)
  double gamma = 7.0;                ///< Tait exponent (1)

  double stiffness() const { return referenceDensity * soundSpeed * soundSpeed / gamma; }  ///< B (Pa)

  /// p(ρ) (Pa).
  [[gnu::always_inline]] double pressure(double rho) const {
    const double c2 = soundSpeed * soundSpeed;
    if (kind == EosKind::Acoustic) return c2 * (rho - referenceDensity);
    const double r = rho / referenceDensity;
    const double r2 = r * r, r3 = r2 * r;
    return stiffness() * (r3 * r3 * r - 1.0);  // γ = 7 unrolled; other γ use pow below
  }

  /// p(ρ) for any γ (the fast path above is exact only for γ = 7).
  double pressureGeneral(double rho) const {
    if (kind == EosKind::Acoustic) return soundSpeed * soundSpeed * (rho - referenceDensity);
    return stiffness() * (std::pow(rho / referenceDensity, gamma) - 1.0);
  }

  /// The inverse: ρ(p) (kg/m³); the Tait inversion ρ = ρ0 (1 + p/B)^(1/γ).
  double density(double p) const {
    if (kind == EosKind::Acoustic) return referenceDensity + p / (soundSpeed * soundSpeed);
    return referenceDensity * std::pow(1.0 + p / stiffness(), 1.0 / gamma);
  }

  /// Local sound speed c = sqrt(dp/dρ) (m/s).
  double localSoundSpeed(double rho) const {
    if (kind == EosKind::Acoustic) return soundSpeed;
    return soundSpeed * std::pow(rho / referenceDensity, 0.5 * (gamma - 1.0));
  }
};

/// The steady shock in front of a piston pushed at speed v (> 0) into the liquid at rest, from the
/// Rankine–Hugoniot jump conditions ρ1 (U − v) = ρ0 U (mass) and p1 = ρ0 U v (momentum) with
/// p1 = p(ρ1): the exact weak-shock solution. For the acoustic law U = (v + √(v² + 4c0²))/2;
/// Tait is solved by bisection on U. Returns {U (m/s), p1 (Pa)}; p1 → ρ0 c0 v as v/c0 → 0.
struct PistonShock {
  double speed;
  double pressure;
};

inline PistonShock pistonShock(const EquationOfState& eos, double v) {
  const double rho0 = eos.referenceDensity;
  auto mismatch = [&](double U) { return eos.pressureGeneral(rho0 * U / (U - v)) - rho0 * U * v; };
  double lo = v + 1e-9 * eos.soundSpeed, hi = eos.soundSpeed + 10.0 * v + 1.0;
  // mismatch(lo) > 0 (ρ1 → ∞), mismatch(hi) < 0 (a shock faster than c0 + 10 v is too weak).
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mismatch(mid) > 0 ? lo : hi) = mid;
  }
  const double U = 0.5 * (lo + hi);
  return {U, rho0 * U * v};
}

}  // namespace rupture::sph
