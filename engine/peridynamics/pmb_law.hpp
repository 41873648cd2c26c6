#pragma once
// The bond law of PMB peridynamics under the name the spec gives it. A PMB bond's pairwise force,
// c s β V_i V_j, is a central spring of stiffness k_b = c β V_i V_j / |ξ| (peridynamics/pmb.hpp
// sets k_b per bond), so the law is the central spring itself: the same type, hence the same
// BondModel alternatives and the same compiled loop as Hookean springs.
#include "core/central_spring_law.hpp"

namespace rupture {

using PmbLaw = CentralSpringLaw;

}  // namespace rupture
