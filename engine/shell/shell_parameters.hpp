#pragma once
// Parameters of the SPH (meshless) Mindlin–Reissner shell, SI units. One struct, validated once
// (validateShellParameters), so that a spec reader, the server and the tests share the checks.
#include <algorithm>
#include <cmath>
#include <string>

#include "damage/lemaitre_chaboche.hpp"
#include "plasticity/von_mises.hpp"

namespace rupture {

struct ShellParameters {
  double thickness = 2.0e-3;             ///< t (m)
  double density = 2770.0;               ///< ρ (kg/m³), AU4G 2024-T351
  ElasticPlasticMaterial material;       ///< E, ν, isotropic hardening (defaults: 2024-T351)
  bool plasticity = true;                ///< false: linear elastic (no return mapping)
  bool damage = false;                   ///< Lemaitre–Chaboche with delay at every layer
  LemaitreChabocheDamage damageLaw;      ///< its ν is taken from `material`
  int thicknessPoints = 5;               ///< Gauss points through the thickness, [2, 7]
  /// Fraction of a stress point's layers that must reach D_c before it fractures, (0, 1]: 1, every
  /// layer (a crack through the whole thickness); 0.2 of 5 layers, the first one. Explicit FE codes
  /// expose the same rule: Radioss's P_thickfail, LS-DYNA's NUMFIP (*MAT_ADD_EROSION).
  double fractureLayerFraction = 1.0;
  double shearCorrection = 5.0 / 6.0;    ///< κ_s of the transverse shear resultant
  /// true: each layer's transverse shear (parabolic through the thickness) enters its yield,
  /// flow and damage; false (the seed's shells): the layers yield in plane stress and the
  /// transverse shear stays elastic.
  bool transverseShearYield = false;
  double smoothingRatio = 1.3;           ///< h / Δ (support radius 2h)
  double hourglassCoefficient = 0.05;    ///< α of the pair-wise hourglass control, [0, 1]
  double rotaryInertiaScale = 1.0;       ///< s_I >= 1: I = s_I ρ t³/12 per unit area
  /// f > 0: the rotary inertia of a node whose kernel reaches thicker stress points (a thickness
  /// step), I = f ρ t_i t_j²/12 with t_j the thickest (never below its own ρ t_i³/12). 1: the
  /// least that keeps the time step the step's translation sets; smaller values are closer to the
  /// node's own inertia and shorten the step as √f.
  double stepRotaryInertia = 1.0;
  double dampingRate = 0.0;              ///< c (1/s): mass-proportional damping, 0 for dynamics
  double courantFactor = 0.8;            ///< fraction of the estimated critical step, (0, 1]
  /// How the critical step is estimated: Bound, from a wave number 2.5/Δ and the thickness ratio
  /// (SphShell's constructor); Spectral, from the largest frequency of the discrete operator
  /// itself, measured by power iteration for each group of terms (shell/shell_spectrum.cpp) and
  /// measured again as fractures change it.
  enum class StepEstimate { Bound, Spectral };
  StepEstimate stepEstimate = StepEstimate::Bound;
  /// true: SphShell::advanceInterval steps each node's terms at its own power-of-two multiple of
  /// the finest step (multi-rate, shell/step_classes.hpp); false: every node at the finest step.
  bool subcycling = false;
};

/// Layers of `layers` that must have failed for a stress point to fracture: ⌈fraction · layers⌉,
/// at least one (a fraction that is a whole number of layers in decimal, such as 0.6 of 5, counts
/// that number, not one more from rounding).
inline int layersToFracture(double fraction, int layers) {
  const int count = static_cast<int>(std::ceil(fraction * layers - 1e-9));
  return std::clamp(count, 1, layers);
}

/// The spec's name of an estimate ("bound", "spectral": tank-impact's plate.step_estimate).
inline const char* stepEstimateName(ShellParameters::StepEstimate e) {
  return e == ShellParameters::StepEstimate::Spectral ? "spectral" : "bound";
}

/// Throws SpecError naming `<prefix>.<field>`.
void validateShellParameters(const ShellParameters& p, const std::string& prefix);

}  // namespace rupture
