#pragma once
// The drop-tower impactor of Caleyron et al. 2013 §4.1: the carriage as a point mass M striking
// the piston, the piston a column of material points joined by axial bar elements, as the seed
// models it ("the piston was represented as a material point connected to beam elements"). One
// degree of freedom per point, the displacement along the motion (down the tank axis, positive
// into the water, zero at t = 0):
//   node 0        the carriage, mass M, speed V at t = 0
//   nodes 1 … n   the piston from its top (struck) face to its wetted face, at rest at t = 0
// The carriage's point is tied to the piston's top by a spring k_c that pushes and pulls (the seed's
// model read as its words allow: the carriage's mass on the beams' top node; `CarriageContact::Tied`,
// the default), or touches it through that spring in compression only (the two may separate and
// strike again: the drop tower as built). The piston's points are joined by springs E A / ℓ
// (ℓ = L / elements) and carry lumped masses ρ A ℓ (half at the two faces). A rigid piston (`two_body`) is one point of mass
// ρ A L. The water pushes the wetted face back with the force the fluid gives the SPH piston
// (piston_drive.hpp). Velocity Verlet, sub-cycled within the fluid's step at the column's own stable
// step. Docs: docs/tank-impact.md#impactor; the bar-impact solution it is tested against:
// docs/references.md#eq-bar-impact.
#include <cstddef>
#include <string>
#include <vector>

#include "rupture/state_archive.hpp"

namespace rupture::fsi {

/// How the carriage and the piston are modelled.
enum class ImpactorModel {
  Rigid,          ///< carriage and piston one rigid body of mass M (the SPH piston itself)
  TwoBody,        ///< carriage and a rigid piston, separate masses, a contact between them
  ElasticPiston   ///< carriage and a piston elastic along its axis (bar elements), a contact between them
};
std::string toString(ImpactorModel model);  ///< "rigid", "two_body", "elastic_piston"

/// How the carriage holds the piston's struck face.
enum class CarriageContact {
  CompressionOnly,  ///< pushes only: the piston may part from the carriage and be struck again
  Tied              ///< the carriage's point joined to the piston's top: the spring also pulls
};
std::string toString(CarriageContact contact);  ///< "compression_only", "tied"

/// The impactor's physical inputs (SI). The defaults are the seed's set-up where it gives them
/// (M = 245 kg, V = 2 or 5 m/s, §2.1; the piston of APX steel, Table 2: E = 211 GPa, ρ = 7700 kg/m³)
/// and stated assumptions where it does not (the piston's length and section; docs/tank-impact.md).
struct ImpactorSpec {
  ImpactorModel model = ImpactorModel::ElasticPiston;
  double mass = 245.0;            ///< carriage M (kg); with `rigid`, carriage and piston together
  double speed = 5.0;             ///< V (m/s) at t = 0, into the water
  double pistonLength = 0.1;      ///< L (m): assumption, the seed does not give it
  double pistonDiameter = 0.08;   ///< of the bar's section (m); default the bore D
  double pistonDensity = 7700.0;  ///< ρ (kg/m³), APX steel (seed Table 2)
  double pistonYoungModulus = 211e9;  ///< E (Pa), APX steel (seed Table 2)
  int pistonElements = 20;        ///< bar elements along L (elastic_piston)
  /// Carriage–piston contact stiffness k_c (N/m); 0 takes the default E A / (5 mm): the axial
  /// stiffness of a 5 mm slice of the piston, so that the flat steel faces add no more compliance
  /// than that (docs/tank-impact.md#impactor).
  double contactStiffness = 0.0;
  /// Tied by default: the seed's model read that way gives its first peaks, its jet and its tongue
  /// (docs/tank-impact.md#the-tied-carriage); compression only is the drop tower as built.
  CarriageContact contact = CarriageContact::Tied;

  double pistonArea() const;   ///< π d²/4 (m²)
  double pistonMass() const;   ///< ρ A L (kg)
  double resolvedContactStiffness() const;
};

class ImpactorColumn {
public:
  /// gravity: its component along the motion (m/s², +9.81 for a fall down the tank axis).
  ImpactorColumn(const ImpactorSpec& spec, double gravity);

  /// Advances by dt (s), sub-cycled at the column's stable step, under faceForce: the water's push
  /// on the wetted face along the motion over the step (N, negative when it resists the piston).
  void advance(double dt, double faceForce);
  /// The largest stable velocity-Verlet step of the column (s), with a margin of 0.9.
  double stableTimeStep() const { return m_stableStep; }

  double faceDisplacement() const { return m_u.back(); }  ///< wetted face (m)
  double faceSpeed() const { return m_v.back(); }         ///< wetted face (m/s)
  double carriageDisplacement() const { return m_u.front(); }
  double carriageSpeed() const { return m_v.front(); }
  /// Force in the carriage–piston contact (N, positive compressive; ≥ 0 unless tied).
  double contactForce() const;
  /// The piston's mean speed Σ m_i v_i / Σ m_i (m/s) and its mass (kg).
  double pistonSpeed() const;
  double pistonMass() const;
  /// Momentum Σ m v (kg m/s) and energy: kinetic, and elastic in the bar and the contact (J).
  double momentum() const;
  double kineticEnergy() const;
  double elasticEnergy() const;
  /// Work the face force has done on the column since t = 0 (J).
  double faceWork() const { return m_faceWork; }
  std::size_t nodes() const { return m_u.size(); }

  /// The points' displacements and speeds and the face work (docs/checkpoints.md).
  void exchangeState(StateArchive& archive);

private:
  void computeForces(double faceForce);

  std::vector<double> m_mass, m_u, m_v, m_f;  ///< per point: kg, m, m/s, N
  double m_elementStiffness = 0;  ///< E A / ℓ (N/m); 0 for a rigid piston
  double m_contactStiffness = 0;  ///< k_c (N/m)
  bool m_tied = false;            ///< the contact also pulls
  double m_gravity = 0;           ///< m/s² along the motion
  double m_stableStep = 0;        ///< s
  double m_faceWork = 0;          ///< J
};

}  // namespace rupture::fsi
