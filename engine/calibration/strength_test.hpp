#pragma once
// Quasi-static tensile strength of a bonded sample, and the fit of the beams' failure stress σ_f to
// a target strength (issue 13 item 2; engine/dem/README.md, "strength").
//
// The test is displacement-driven uniaxial tension as in calibration/calibration.hpp (faces X_min and X_max
// held in x, free laterally, Cundall-damped relaxation), in two stages:
//  1. Elastic: relax at the strain ε_e of the elastic measurement with failure off. Before the first
//     break the response is linear in ε and every beam's σ_eq (eq. 1) is homogeneous of degree one in
//     the displacements, so the quasi-static crack-onset strain is exact: ε_onset = ε_e σ_f / max σ_eq.
//  2. Damage: start from the elastic field scaled to (1 − Δ/2) ε_onset (relaxed and recorded), then
//     raise the strain by steps of Δ ε_onset (affine increments of the X positions, Δ =
//     options.strainIncrement; none lands on ε_onset, where rounding decides the first break), relaxing at each
//     with failure and contact on until the mean face stress σ̄ (seed eq. 4) settles and no bond broke
//     over a check interval. tensile_strength = the largest settled σ̄; the test stops once σ̄ falls
//     below stopFraction × that peak, or at maxStrainFactor × ε_onset.
// With a linear beam law, a stress threshold and small strains, the whole quasi-static curve scales
// with σ_f (stress and strain alike): the fit rescales σ_f by S_target / S and checks with one more
// test (a secant step if contact or geometric non-linearity moved it by more than the tolerance).
#include <atomic>
#include <cstddef>
#include <functional>

#include "bonded/bonded_system.hpp"
#include "calibration/calibration.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

struct StrengthOptions {
  CalibrationOptions elastic;         ///< strain ε_e, damping, tolerance, cancel, progress of stage 1
  double strainIncrement = 0.02;      ///< Δ, step of the damage stage as a fraction of ε_onset
  double stopFraction = 0.5;          ///< stop once σ̄ < stopFraction × peak after the peak
  double maxStrainFactor = 6.0;       ///< stop at this multiple of ε_onset
  double stressTolerance = 2e-3;      ///< relative change of σ̄ over a check interval to call a step settled
  std::size_t maxStepsPerIncrement = 200000;
};

struct StrengthResult {
  ElasticProperties elastic;        ///< E, ν of the elastic stage
  double crackOnsetStrain = 0;      ///< ε at which the first bond reaches σ_f (1)
  double tensileStrength = 0;       ///< peak settled σ̄ (Pa)
  double strainAtPeak = 0;          ///< (1)
  double brokenFractionAtPeak = 0;  ///< broken bonds / initial bonds at the peak (1)
  std::size_t increments = 0;       ///< damage-stage strain steps
  std::size_t steps = 0;            ///< relaxation steps of both stages
  bool completed = false;           ///< reached the post-peak drop or the strain limit (not cancelled)
};

/// Runs the test on a copy of the sample (its beams' failure stress must be > 0).
StrengthResult measureTensileStrength(const BondedSystem& sample, const SampleSpec& spec,
                                      const StrengthOptions& options = {});

struct StrengthFit {
  double failureStress = 0;   ///< fitted σ_f (Pa)
  StrengthResult achieved;    ///< the test with the fitted σ_f
  int evaluations = 0;        ///< strength tests run
  bool cancelled = false;
};

/// Fits the beams' failure stress so that the quasi-static tensile strength is targetStrength (Pa),
/// within relativeTolerance (up to four tests). Throws CalibrationError if the sample never breaks.
StrengthFit fitFailureStress(const BondedSystem& sample, const SampleSpec& spec, double targetStrength,
                             const StrengthOptions& options = {}, double relativeTolerance = 0.01);

}  // namespace rupture
