#pragma once
// Rankine equivalent stress, eq. (1) of Longchamp et al. (CSMA 2024), after André et al. (2013):
//   σ_eq = ½ (σ_Nmax + √(σ_Nmax² + 4 τ_max²))
// σ_Nmax: largest normal stress in the beam section (traction + bending, tension positive);
// τ_max: shear stress from torsion. Pure compression without torsion gives σ_eq <= 0.
#include <cmath>

namespace rupture {

inline double rankineEquivalentStress(double maxNormalStress, double maxShearStress) {
  return 0.5 * (maxNormalStress +
                std::sqrt(maxNormalStress * maxNormalStress + 4.0 * maxShearStress * maxShearStress));
}

/// The bond breaks (irreversibly) when the equivalent stress reaches the threshold σ_f.
struct RankineCriterion {
  double failureStress;  ///< σ_f (Pa)
  bool breaks(double equivalentStress) const { return equivalentStress >= failureStress; }
};

}  // namespace rupture
