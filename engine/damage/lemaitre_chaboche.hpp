#pragma once
// Lemaitre–Chaboche ductile damage with a delay effect, as used for the AU4G plate of the tank-
// impact campaign (Caleyron et al. 2013, §5.3.1, eqs. (9)–(12); docs/references.md#eq-lemaitre):
//
//   triaxiality function  R_ν(η) = 2/3 (1 + ν) + 3 (1 − 2ν) η²,   η = σ_H / σ_eq
//   threshold (9)         f_D = R_ν p − ε_p^s <= 0: no damage while R_ν p <= ε_p^s
//   undelayed rate (10)-(11)  Ḋ_nc = D_c / (ε_p^c − ε_p^s) · R_ν · ṗ          (f_D > 0)
//   delayed rate (12)     Ḋ = (1/τ_c) (1 − exp(−a ⟨D_nc − D⟩)),   ⟨x⟩ = max(x, 0)
//   fracture              D >= D_c: the point carries no stress
//   coupling              σ = (1 − D) σ~, σ~ the effective stress of the undamaged plasticity
//                         (strain equivalence, Lemaitre 1985)
//
// Eq. (10) is Lemaitre's Ḋ = (Y/S) ṗ with the elastic energy density release rate
//   Y = σ~_eq² R_ν / (2E)  (eq. energyReleaseRate below)
// written for a flow stress that no longer hardens, S = σ~_eq² (ε_p^c − ε_p^s) / (2 E D_c), so that
// a uniaxial path (R_ν = 1) reaches D_c at p = ε_p^c. The delay (Ladevèze 1991; Allix & Deü 1997)
// bounds the damage rate by 1/τ_c, which gives the softening problem a characteristic length
// l_car ≈ c τ_c ln(Δσ/σ_lim) (seed eq. 13).
//
// Time integration per step (one material point, given Δp over dt and the current stress state):
// D_nc is integrated exactly for the part of Δp beyond the threshold; D by backward Euler on (12)
// with D_nc at the end of the step, solved on [D_n, max(D_n, D_nc)], so that D never overtakes D_nc
// and (D − D_n)/dt <= 1/τ_c for any dt.
#include <span>
#include <string>

namespace rupture {

struct LemaitreChabocheDamage {
  double thresholdPlasticStrain = 0.08;   ///< ε_p^s (1)
  double criticalPlasticStrain = 0.21;    ///< ε_p^c (1), > ε_p^s
  double criticalDamage = 0.3;            ///< D_c (1), in (0, 1)
  double delayTime = 3.0e-7;              ///< τ_c (s), inverse of the largest damage rate
  double delaySharpness = 1.0;            ///< a (1)
  double poissonRatio = 0.33;             ///< ν of the material (1), enters R_ν

  double triaxialityFunction(double eta) const {
    return 2.0 / 3.0 * (1.0 + poissonRatio) + 3.0 * (1.0 - 2.0 * poissonRatio) * eta * eta;
  }
  /// Slope D_c/(ε_p^c − ε_p^s) of eq. (10).
  double undelayedSlope() const {
    return criticalDamage / (criticalPlasticStrain - thresholdPlasticStrain);
  }
  /// Eq. (12): delayed rate for the current pair (D_nc, D) (1/s).
  double delayedRate(double undelayed, double damage) const;
};

/// Throws SpecError naming `<prefix>.<field>` (threshold_plastic_strain, critical_plastic_strain,
/// critical_damage, delay_time, delay_sharpness, poisson_ratio).
void validateDamage(const LemaitreChabocheDamage& d, const std::string& prefix);

/// Y = σ~_eq² R_ν / (2E) (J/m³), σ~_eq the effective von Mises stress.
double energyReleaseRate(const LemaitreChabocheDamage& d, double effectiveVonMises,
                         double youngModulus, double triaxiality);

/// η = σ_H / σ_eq; 0 for a vanishing deviator.
inline double triaxiality(double hydrostatic, double vonMises) {
  return vonMises > 0.0 ? hydrostatic / vonMises : 0.0;
}

/// Damage state of one material point.
struct DamageState {
  double undelayed = 0.0;  ///< D_nc
  double damage = 0.0;     ///< D
  bool fractured = false;  ///< D reached D_c (irreversible)
};

/// Advances one point over a step: p goes from `plasticStrain` to `plasticStrain + dp` at
/// triaxiality η, over dt. Returns true when the point fractures during this step.
bool advanceDamage(const LemaitreChabocheDamage& d, DamageState& state, double plasticStrain,
                   double dp, double eta, double dt);

/// Array form: one entry per material point.
void advanceDamage(const LemaitreChabocheDamage& d, std::span<DamageState> states,
                   std::span<const double> plasticStrain, std::span<const double> dp,
                   std::span<const double> eta, double dt);

/// Multiplier (1 − D) of the effective stress; 0 once fractured.
inline double stressFactor(const DamageState& s) { return s.fractured ? 0.0 : 1.0 - s.damage; }

}  // namespace rupture
