#pragma once
// Named material presets of the tank-impact campaign (Caleyron et al. 2013): the AU4G (2024-T351) bottom plate
// and the steel of the cylinder. Every value and its source: docs/shell-and-damage.md, "Materials".
#include <string>

#include "damage/lemaitre_chaboche.hpp"
#include "plasticity/von_mises.hpp"

namespace rupture {

struct MaterialPreset {
  const char* name;
  double density;                   ///< kg/m³
  ElasticPlasticMaterial material;  ///< E, ν, Johnson–Cook hardening without rate term
  LemaitreChabocheDamage damage;    ///< delayed Lemaitre–Chaboche parameters
};

/// A metal with Johnson & Cook hardening σ_y = A + B ε_p^n (Pa) and Lemaitre–Chaboche damage of the
/// same Poisson ratio (the damage's default thresholds), for the presets below.
inline MaterialPreset johnsonCookPreset(const char* name, double density, double youngModulus, double poissonRatio,
                                        double a, double b, double n) {
  MaterialPreset p{name, density, {}, {}};
  p.material.youngModulus = youngModulus;
  p.material.poissonRatio = poissonRatio;
  p.material.hardening = {HardeningKind::johnsonCook, a, b, n};
  p.damage = LemaitreChabocheDamage{};
  p.damage.poissonRatio = poissonRatio;
  return p;
}

/// AU4G = 2024-T351: E, ν (ASM handbook values), Johnson & Cook (1983) A, B, n and density; ε_p^c
/// from the Johnson & Cook (1985) fracture fit at η = 1/3; see the doc for D_c, ε_p^s, τ_c, a.
inline MaterialPreset au4g2024T351() {
  return johnsonCookPreset("au4g_2024_t351", 2770.0, 73.1e9, 0.33, 265.0e6, 426.0e6, 0.34);
}

/// AU4G 2024-T351 with the values Caleyron et al. 2013 give: density, E, ν of its Table 1 (ρ = 2780
/// kg/m³, σ_y = 325 MPa, which the Johnson & Cook fit above meets at 0.2 % plastic strain: 317
/// MPa) and the delayed-damage parameters of its Table 6 (Suffis 2004): ε_p^s = 0.03,
/// ε_p^c = 0.25, D_c = 0.23, τ_c = 0.1 µs, a = 2. The tank-impact scenario's default plate.
inline MaterialPreset au4g2024T351Seed() {
  MaterialPreset p = au4g2024T351();
  p.name = "au4g_2024_t351_seed";
  p.density = 2780.0;
  p.damage.thresholdPlasticStrain = 0.03;
  p.damage.criticalPlasticStrain = 0.25;
  p.damage.criticalDamage = 0.23;
  p.damage.delayTime = 1.0e-7;
  p.damage.delaySharpness = 2.0;
  return p;
}

/// Cylinder steel: the seed's grade table is lost; 4340 steel of Johnson & Cook (1983)
/// (A, B, n, density, G = 77.5 GPa → E = 200 GPa with ν = 0.29) stands in.
inline MaterialPreset steel4340() {
  MaterialPreset p = johnsonCookPreset("steel_4340", 7830.0, 200.0e9, 0.29, 792.0e6, 510.0e6, 0.26);
  // ε_p^c at η = 1/3 from the Johnson & Cook (1985) 4340 fit (D1 = 0.05, D2 = 3.44, D3 = −2.12):
  // 0.05 + 3.44 exp(−2.12/3) = 1.75 is far beyond what the impact reaches: the cylinder does not fail.
  p.damage.criticalPlasticStrain = 1.75;
  p.damage.thresholdPlasticStrain = 0.5;
  return p;
}

/// "au4g_2024_t351", "au4g_2024_t351_seed" or "steel_4340"; throws SpecError(field) otherwise.
MaterialPreset materialPreset(const std::string& name, const std::string& field);

}  // namespace rupture
