#pragma once
// The BondModel of a law with the failure criterion a spec names: one template the central-force
// styles share (springs, PMB), so that a criterion is spelled once.
#include <stdexcept>
#include <string>

#include "bonded/bond_model.hpp"

namespace rupture {

template <class Law>
BondModel withCriterion(const Law& law, const std::string& criterion, double alpha = 0.0) {
  if (criterion == "critical_stretch") return BondModelOf<Law, CriticalStretchCriterion>{law, {alpha}};
  if (criterion == "critical_energy") return BondModelOf<Law, CriticalEnergyCriterion>{law, {}};
  if (criterion == "stress") return BondModelOf<Law, StressThresholdCriterion>{law, {}};
  if (criterion == "griffith") return BondModelOf<Law, GriffithEnergyCriterion>{law, {}};
  throw std::invalid_argument("unknown failure criterion \"" + criterion + "\"");
}

}  // namespace rupture
