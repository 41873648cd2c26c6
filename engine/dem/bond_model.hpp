#pragma once
// The material model of a bonded system: one bond law and one failure criterion, chosen by the
// spec (material.model and its criterion). A std::variant of the supported pairs, visited once per
// loop: the templated bonded loop (core/bond_loop.hpp) runs inside, so nothing is dispatched per
// bond. Adding a law is its header, one line per meaningful criterion here, and its set-up in
// dem/bond_model.cpp.
#include <string>
#include <variant>

#include "core/cancellation.hpp"
#include "damage/critical_energy.hpp"
#include "damage/critical_stretch.hpp"
#include "damage/griffith_energy.hpp"
#include "damage/rankine.hpp"
#include "damage/stress_threshold.hpp"
#include "dem/beam_law.hpp"
#include "lattice/born_law.hpp"
#include "lattice/central_spring_law.hpp"

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

namespace rupture {

struct SampleSpec;
struct MaterialSpec;
struct BeamParameters;
class BondedSystem;

/// Chooses the law and criterion of `material` and sets every bond's constants (stiffness,
/// threshold, strength from material.no_failure_regions), the beam parameters and the contact.
/// The sample's particles and bonds must be built (volumes set); call initialize() afterwards.
/// Grain and inclusion placement poll `cancel` (RunCancelled).
void assignMaterial(BondedSystem& system, const SampleSpec& sample, const MaterialSpec& material,
                    const Cancellation& cancel = {});

/// Gives a built beam sample other beams (a calibration's result) with what follows from them as
/// the spec would have given it: the contact modulus and Poisson ratio where the spec left them to
/// their defaults (MaterialSpec::contactModulusFromBeams), and the damping wave speed. Without this,
/// the strength measured after an elastic fit is that of the old beams' contact law, not the one a
/// spec with the fitted beams runs with.
void assignBeams(BondedSystem& system, const MaterialSpec& material, const BeamParameters& beams);

}  // namespace rupture
