#pragma once
// The material model of a bonded system: one bond law and one failure criterion, chosen by the
// spec (material.model and its criterion). A std::variant of the supported pairs, visited once per
// loop: the templated bonded loop (core/bond_loop.hpp) runs inside, so nothing is dispatched per
// bond. Adding a law is its header, one line per meaningful criterion here, and its material style
// (bonded/materials/), which parses its parameters and sets its bonds up.
#include <string>
#include <variant>

#include "core/central_spring_law.hpp"
#include "damage/critical_energy.hpp"
#include "damage/critical_stretch.hpp"
#include "damage/griffith_energy.hpp"
#include "damage/rankine.hpp"
#include "damage/stress_threshold.hpp"
#include "dem/beam_law.hpp"
#include "lattice/born_law.hpp"
#include "peridynamics/pmb_law.hpp"

namespace rupture {

template <class L, class C>
struct BondModelOf {
  using Law = L;
  using Criterion = C;
  L law;
  C criterion;
};

/// The beam model reads its parameters from BondedSystem::beam (the calibration fit varies them).
using BeamModel = BondModelOf<BeamLaw, RankineCriterion>;

// Central springs serve Hookean lattices and PMB (PmbLaw is CentralSpringLaw): one set of lines.
using BondModel = std::variant<BeamModel,
                               BondModelOf<CentralSpringLaw, CriticalStretchCriterion>,
                               BondModelOf<CentralSpringLaw, CriticalEnergyCriterion>,
                               BondModelOf<CentralSpringLaw, StressThresholdCriterion>,
                               BondModelOf<CentralSpringLaw, GriffithEnergyCriterion>,
                               BondModelOf<BornLaw, CriticalStretchCriterion>,
                               BondModelOf<BornLaw, CriticalEnergyCriterion>,
                               BondModelOf<BornLaw, StressThresholdCriterion>,
                               BondModelOf<BornLaw, GriffithEnergyCriterion>>;

/// "law/criterion", e.g. "born/griffith" (for logs and tests).
std::string describe(const BondModel& model);

}  // namespace rupture
