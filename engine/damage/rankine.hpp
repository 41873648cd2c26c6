#pragma once
// Rankine equivalent stress, eq. (1) of Longchamp et al. (CSMA 2024), after André et al. (2013):
//   σ_eq = ½ (σ_Nmax + √(σ_Nmax² + 4 τ_max²))
// σ_Nmax: largest normal stress in the beam section (traction + bending, tension positive);
// τ_max: shear stress from torsion. Pure compression without torsion gives σ_eq <= 0.
#include <cmath>

#include "core/bond_law.hpp"

namespace rupture {

inline double rankineEquivalentStress(double maxNormalStress, double maxShearStress) {
  return 0.5 * (maxNormalStress +
                std::sqrt(maxNormalStress * maxNormalStress + 4.0 * maxShearStress * maxShearStress));
}

/// Failure measure of the beam law: the bond breaks (irreversibly) when σ_eq reaches σ_f, the
/// per-bond threshold (Pa).
struct RankineCriterion {
  static constexpr const char* kName = "rankine";
  static constexpr bool kNodalShift = false;
  double measure(const BondResponse& r) const { return r.equivalentStress; }
};

}  // namespace rupture
