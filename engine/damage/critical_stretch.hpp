#pragma once
// Critical stretch (Silling & Askari 2005; LAMMPS peri/pmb): the bond breaks when its stretch
// s = (L − L0)/L0 exceeds s0 (the per-bond threshold). With the compression term α (LAMMPS), each
// node carries s0_k = s00 − α s_min,k, s_min,k being its most compressive (smallest) bond stretch at
// the previous evaluation, and a bond breaks when s > min(s0_i, s0_j), i.e. when
//   s + α max(s_min,i, s_min,j) > s00.
// The loop adds that nodal shift to the measure; s_min is gathered after each evaluation.
#include "core/bond_law.hpp"

namespace rupture {

struct CriticalStretchCriterion {
  static constexpr const char* kName = "critical_stretch";
  static constexpr bool kNodalShift = true;
  double alpha = 0.0;  ///< compression term α (1); 0: plain critical stretch
  double measure(const BondResponse& r) const { return r.stretch; }
};

}  // namespace rupture
