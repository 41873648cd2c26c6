#pragma once
// Silling's local damping of bonds around damage (Bobaru et al. 2016 eq. 2.34 as PeriLab documents
// it; docs/references.md#eq-pd): a dashpot
// along each intact bond, proportional to the bond's rate of extension and to the mean damage of
// its two ends, so that it damps the waves released by breaking bonds and leaves intact material
// (φ̄ = 0) undamped:
//   F_damp = φ̄ d k L0 (|η_n| − |η_{n−1}|) / (Δt v0),   along the bond, resisting its extension,
// with φ̄ = (φ_i + φ_j)/2, d the coefficient, k the bond's axial stiffness (N/m; PeriLab's
// micromodulus c times the partners' volumes over L0, so k L0 ė/v0 is PeriLab's c ė/v0 as a
// force), ė from the lengths at this and the previous evaluation, and v0 = √(E/ρ) the bar wave
// speed (PeriLab's page prints E/ρ; only the square root is a speed).
#include <cstddef>

namespace rupture {

struct SillingDamping {
  double coefficient = 0.0;             ///< d (1)
  double inverseStepTimesSpeed = 0.0;   ///< 1 / (Δt v0) (s/m · 1/s)
  const double* damage = nullptr;       ///< φ per particle (1)
  double* previousLength = nullptr;     ///< |η| per bond at the previous evaluation (m); updated

  /// Axial damping force on the bond, tension positive (N), and the new previous length stored.
  [[gnu::always_inline]] double axialForce(std::size_t b, int i, int j, double length, double axialStiffness,
                                           double restLength) const {
    const double extension = length - previousLength[b];
    previousLength[b] = length;
    const double meanDamage = 0.5 * (damage[i] + damage[j]);
    return meanDamage * coefficient * axialStiffness * restLength * extension * inverseStepTimesSpeed;
  }
};

}  // namespace rupture
