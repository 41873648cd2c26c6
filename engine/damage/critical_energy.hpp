#pragma once
// Critical bond energy (Foster, Silling & Chen 2011; PeriLab "Critical Energy";
// docs/references.md#eq-pd): the bond breaks when the elastic energy it stores reaches the critical value (the per-bond threshold, J).
// Compressed bonds never break (PeriLab's default): their measure is 0.
#include "core/bond_law.hpp"

namespace rupture {

struct CriticalEnergyCriterion {
  static constexpr const char* kName = "critical_energy";
  static constexpr bool kNodalShift = false;
  double measure(const BondResponse& r) const { return r.stretch > 0.0 ? r.energy : 0.0; }
};

}  // namespace rupture
