#pragma once
// Gives a built sample its material: the style's law, criterion and per-bond constants
// (bonded/materials/), then what every style shares — interblock critical values, grain boundaries,
// inclusions, bond disorder, anisotropic damage's fibres, no-failure regions, contact and local
// damping.
#include "core/cancellation.hpp"

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
