#pragma once
// Stress threshold for lattice springs (Yu et al. 2019; docs/references.md#eq-lattice): the bond
// breaks when its normal
// stress F_n / A_b reaches σ_c, with A_b the area a bond stands for (l·t in 2D, l² in 3D). The
// loop compares F_n with the per-bond threshold σ_c A_b (N); compression never breaks.
#include "core/bond_law.hpp"

namespace rupture {

struct StressThresholdCriterion {
  static constexpr const char* kName = "stress";
  static constexpr bool kNodalShift = false;
  double measure(const BondResponse& r) const { return r.normalForce; }
};

}  // namespace rupture
