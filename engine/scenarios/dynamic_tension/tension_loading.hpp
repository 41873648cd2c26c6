#pragma once
// Uniaxial tension along x of a bonded sample (Longchamp et al., CSMA 2024, section 3.1, Fig. 1):
// the elements of the X_min face have their x-velocity held at zero (U_x = 0), those of the X_max
// face an imposed x-velocity V(t) rising sinusoidally from 0 to V_max over a ramp time Δt, then
// constant; the lateral faces are free, and every other degree of freedom of the face elements
// (y, z, rotation) stays free too.
//
//   V(t) = V_max · ½ (1 − cos(π t / Δt))  for t < Δt,  V_max after            (Fig. 1b)
//   ε = (L − L0) / L0,   ε̇ = V_max / L0                                        (eq. 3)
//   σ_Xmin = F_Xmin / S,  σ_Xmax = F_Xmax / S,  σ̄ = ½ (σ_Xmin + σ_Xmax)        (eq. 4)
//
// Conventions of this implementation:
// - Face groups: elements with x_i − R_i within 0.5 R_DE of the smallest x_k − R_k (X_min), and
//   symmetrically x_i + R_i within 0.5 R_DE of the largest x_k + R_k (X_max).
// - L0 = distance between the mean centre abscissae of the two face groups (the length over which
//   the sample deforms: the face elements move rigidly in x). L − L0 is the x-displacement of the
//   X_max face, read from the positions, so ε is exactly the imposed displacement / L0.
// - S = L_y × t in 2D (lateral box size times the out-of-plane thickness t = R_DE of the sample
//   builder), L_y × L_z in 3D.
// - Face forces: after a step, ParticleStore::f holds each element's total load (bonds + contact).
//   The X_min elements are pulled towards +x in tension, the X_max ones towards −x, so
//   σ_Xmin = +Σ_Xmin f_x / S and σ_Xmax = −Σ_Xmax f_x / S (tension positive).
#include <cstdint>
#include <vector>

#include "bonded/bonded_system.hpp"
#include "samples/sample_builder.hpp"
#include "bonded/sample_spec.hpp"

namespace rupture {

/// The loaded faces and the measures of eqs. 3–4, fixed once the sample is built.
struct TensionGeometry {
  std::vector<std::int32_t> xmin, xmax;  ///< element indices of the two face groups
  double xminCentre = 0, xmaxCentre = 0; ///< mean centre abscissa of each group (m)
  double gaugeLength = 0;                ///< L0 (m)
  double section = 0;                    ///< S (m²)
  double volume = 0;                     ///< box volume used for densities (m³; L_x L_y t in 2D)
  double bulkDensity = 0;                ///< ρ of the porous sample = Σ m_i / volume (kg/m³)
};

/// Finds the face groups and the measures; throws std::runtime_error if a face has no element.
TensionGeometry tensionGeometry(const BondedSystem& system, const SampleSpec& sample,
                                const SampleReport& report);

/// The imposed X_max velocity of Fig. 1b. rampTime = 0: V_max from t = 0.
struct VelocityRamp {
  double maxVelocity = 0;  ///< V_max (m/s)
  double rampTime = 0;     ///< Δt (s)
  double velocity(double t) const;
  /// Imposed displacement ∫₀ᵗ V (m).
  double displacement(double t) const;
  /// The time at which the imposed displacement reaches u (s); inverse of displacement().
  double timeToReach(double u) const;
};

struct FaceStresses {
  double xmin = 0, xmax = 0, mean = 0;  ///< σ_Xmin, σ_Xmax, σ̄ (Pa), tension positive
};

/// Boundary conditions and measures of one tension run.
class TensionLoading {
public:
  TensionLoading(TensionGeometry geometry, double strainRate, double rampTime);

  /// Marks the x-velocity of the face elements as prescribed and installs system.prescribe.
  /// Call with the positions of the reference (undeformed) state: strain() is measured from them.
  void install(BondedSystem& system);
  /// Only the reference of strain(): the probe's abscissa in `reference` (the whole sample,
  /// undeformed), for a caller that prescribes the faces on a sub-domain (prescribeFaces) and
  /// never installs the loading on the whole sample.
  void setReference(const ParticleStore& reference);
  /// The same prescription on a sub-domain, whose face elements are `xmin` and `xmax` in its own
  /// numbering (distributed/subdomain.hpp): install() on the whole sample, or setReference(), first.
  void prescribeFaces(BondedSystem& part, std::vector<std::int32_t> xmin, std::vector<std::int32_t> xmax) const;

  /// ε from the X_max face displacement (1).
  double strain(const ParticleStore& p) const { return strainAt(p.x[m_probe]); }
  /// ε when the probe element (probe(): an X_max element) is at x = probeX (m).
  double strainAt(double probeX) const { return (probeX - m_probeX0) / m_geometry.gaugeLength; }
  std::int32_t probe() const { return m_probe; }
  /// σ_Xmin, σ_Xmax, σ̄ from the loads of the last step: O(face elements).
  FaceStresses stresses(const ParticleStore& p) const;
  /// The same from the faces' summed x-loads (N), each added over its elements in index order.
  FaceStresses stressesFrom(double forceXmin, double forceXmax) const;

  const TensionGeometry& geometry() const { return m_geometry; }
  const VelocityRamp& ramp() const { return m_ramp; }
  double strainRate() const { return m_strainRate; }

private:
  TensionGeometry m_geometry;
  double m_strainRate;
  VelocityRamp m_ramp;
  std::int32_t m_probe = 0;  ///< an X_max element: its x-displacement is the face displacement
  double m_probeX0 = 0;
};

/// Affine (Voigt) estimate of the P-wave speed of the bond network along x: the axial beam
/// stiffnesses k_b = E S_b / L0_b summed as M = Σ_b k_b L0_b² n_x⁴ / V, C = √(M / ρ). It ignores
/// the non-affine relaxation of a disordered packing, so it bounds the real wave speed from above.
double affineWaveSpeed(const BondedSystem& system, const TensionGeometry& geometry);

}  // namespace rupture
